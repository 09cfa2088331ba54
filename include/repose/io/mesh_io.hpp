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

/// Parses the bytes of a mesh file held in memory exactly as read_mesh() parses a file: the extension of
/// `name` selects the format and `name` starts every error message ("NAME: problem").
TriangleMesh read_mesh_from_memory(const std::string& bytes, const std::string& name);

/// Writes a binary STL file atomically (temporary file + rename). Throws repose::Error on failure.
void write_stl(const TriangleMesh& mesh, const std::string& path);

}  // namespace repose
