// Reading and writing particle surface meshes.
#pragma once

#include <string>

#include "repose/geometry/types.hpp"

namespace repose {

/// Reads a triangle mesh from STL (ASCII or binary), OBJ, PLY or OFF, chosen by content and extension.
/// Polygons are triangulated. The result is not validated; call validate_mesh(). Throws repose::Error
/// ("FILE: problem") when the file cannot be opened, is empty, truncated, malformed, or claims more
/// elements than its size can hold.
TriangleMesh read_mesh(const std::string& path);

/// Writes a binary STL file atomically (temporary file + rename). Throws repose::Error on failure.
void write_stl(const TriangleMesh& mesh, const std::string& path);

}  // namespace repose
