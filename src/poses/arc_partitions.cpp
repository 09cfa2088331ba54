// The landscape's arc partitions: ArcPartitionsT over double (arc_partitions_impl.hpp), compiled once.
#include "arc_partitions_impl.hpp"

namespace repose::detail {

template class ArcPartitionsT<double>;

}  // namespace repose::detail
