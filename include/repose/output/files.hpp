// Writing result files: never half-written. Every file is written to a temporary name in the same directory
// and renamed into place, so an interrupted run leaves either the old file or the new one.
#pragma once

#include <cstddef>
#include <string>

namespace repose {

/// `synced`: the data reach the disk before the rename (and the rename before returning), so the file
/// survives a power cut too, not only a killed process. For checkpoints; costs a disk flush.
enum class FileDurability { normal, synced };

/// Writes `content` to `path` atomically. Throws repose::Error ("PATH: cannot write: reason").
void write_file_atomically(const std::string& path, const std::string& content,
                           FileDurability durability = FileDurability::normal);

/// Removes what interrupted writes of `path` left behind (its temporary files, `path.tmp-PID`).
void remove_temporaries(const std::string& path);

/// Reads a whole text file (a result file being merged, for instance). Throws repose::Error ("PATH: cannot
/// read: reason") if it cannot be opened or is larger than `max_bytes`.
std::string read_text_file(const std::string& path, std::size_t max_bytes = std::size_t{1} << 30);

/// Creates `dir` (and parents) if needed and checks it is a writable directory. Throws repose::Error.
void ensure_output_directory(const std::string& dir);

/// Before a run that ends by writing the file `path`: creates its directory if needed and checks that it is
/// writable and that `path` is not a directory. Throws repose::Error.
void ensure_output_file(const std::string& path);

}  // namespace repose
