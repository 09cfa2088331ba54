// libFuzzer harness for the rest-pose result reader (parse_poses_json: the files `repose merge` reads).
//
// Oracle: the text is rejected with repose::Error, or the study it gives can be written back out as JSON,
// CSV and a table (what `repose merge` does with it) without a crash, and the JSON it writes is read back.
#include <cstddef>
#include <cstdint>
#include <string>

#include "repose/error.hpp"
#include "repose/poses/study.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  repose::PosesStudy study;
  try {
    study = repose::parse_poses_json(text, "fuzz/poses.json");
  } catch (const repose::Error&) {
    return 0;
  } catch (...) {
    __builtin_trap();
  }
  try {
    const std::string json = repose::poses_json(study);
    (void)repose::poses_csv(study);
    (void)repose::poses_table(study);
    (void)repose::parse_poses_json(json, "fuzz/poses-rewritten.json");
  } catch (...) {
    __builtin_trap();
  }
  return 0;
}
