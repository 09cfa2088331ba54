// The double instantiations of the spherical helpers (spherical.hpp), compiled once.
#include "spherical.hpp"

namespace repose::detail {

template Vec3 chord_point<double>(const Vec3&, const Vec3&, const double&);
template double cut<double>(const Vec3&, const Vec3&, const Vec3&);
template void clip_interval<double>(const Vec3&, const Vec3&, const Vec3&, double&, double&);
template void clip_polygon<double>(const std::vector<Vec3>&, const Vec3&, std::vector<Vec3>&);
template double spherical_area<double>(const std::vector<Vec3>&);

}  // namespace repose::detail
