// Reading and writing particle surface meshes.
#pragma once

#include <string>

#include "repose/geometry/types.hpp"

namespace repose {

/// Reads a mesh from STL (ASCII or binary, told apart by content), OBJ, PLY (ASCII or binary, either byte
/// order), OFF, or an XYZ point cloud, chosen by the extension (.stl, .obj, .ply, .off, .xyz, any case).
/// Each file is read once, by repose's own parser for its format. The vertices are those the file lists, in
/// its order, in the file's length unit; an STL's facet corners with identical coordinates are one vertex
/// (coordinates as stored: float). Polygons are triangulated as a fan keeping their winding (a quad with a
/// concave corner from that corner); lines, points and faces of fewer than 3 vertices are no part of the
/// surface. A file with vertices but no faces (XYZ always) gives a point cloud: vertices, no triangles.
/// The result is not validated; call validate_mesh(). Throws repose::Error ("FILE: problem", naming the
/// line or element where it can) when the file cannot be opened, is empty, truncated or malformed, has no
/// vertices, has a face index out of range, or claims more elements than its size can hold.
TriangleMesh read_mesh(const std::string& path);

/// Parses the bytes of a mesh file held in memory exactly as read_mesh() parses a file: the extension of
/// `name` selects the format and `name` starts every error message ("NAME: problem").
TriangleMesh read_mesh_from_memory(const std::string& bytes, const std::string& name);

/// Writes a binary STL file atomically (temporary file + rename). Throws repose::Error on failure.
void write_stl(const TriangleMesh& mesh, const std::string& path);

/// Writes an OBJ file (vertices to 17 significant digits, triangles) atomically. Throws repose::Error on
/// failure.
void write_obj(const TriangleMesh& mesh, const std::string& path);

}  // namespace repose
