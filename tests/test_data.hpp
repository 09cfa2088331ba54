// The test data files (tests/data/), one helper for every test source.
#pragma once

#include <string>

namespace repose::test {

inline std::string data_file(const std::string& name) { return std::string(REPOSE_TEST_DATA) + "/" + name; }

}  // namespace repose::test
