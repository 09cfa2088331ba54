// Writing result files: never half-written. Every file is written to a temporary name in the same directory
// and renamed into place, so an interrupted run leaves either the old file or the new one.
#pragma once

#include <string>

namespace repose {

/// Writes `content` to `path` atomically. Throws repose::Error ("PATH: cannot write: reason").
void write_file_atomically(const std::string& path, const std::string& content);

/// Creates `dir` (and parents) if needed and checks it is a writable directory. Throws repose::Error.
void ensure_output_directory(const std::string& dir);

}  // namespace repose
