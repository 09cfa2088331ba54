// Built-in particle shapes, created from spec strings such as "cylinder:r=0.67,h=0.67,n=64".
//
// Body frames (the frame of the returned mesh; all shapes are centred on their centre of mass):
// - box:x=X,y=Y,z=Z          edges X, Y, Z along body x, y, z.
// - cylinder:r=R,h=H[,n=N]   regular N-gon prism (3 ≤ N ≤ 4096, default 64; qhull merging the caps grows
//                            steeply with N) inscribed in the circle of radius R, axis
//                            along body z, one rim vertex on +x.
// - ellipsoid:a=A,b=B,c=C[,n=F]   semi-axes A, B, C along body x, y, z; a geodesic icosphere of frequency F
//                            (20·F² triangles, default F = 10 → 2000) with its vertices on the ellipsoid.
// - tetrahedron:edge=A       regular tetrahedron; one face parallel to the body xy plane at
//                            z = −A·sqrt(2/3)/4, the opposite vertex on +z, bottom vertices at azimuths 90°,
//                            210°, 330° (one on +y).
// - irregular:seed=S[,size=D][,n=F]   a jagged, non-convex random particle (like Fig 9 of the paper): a
//                            star-shaped surface with random radii on an icosphere of frequency F (default
//                            4), stretched along random axes; D (default 1) is its largest extent. Same seed
//                            → same mesh, on every platform.
#pragma once

#include <string>

#include "repose/geometry/types.hpp"

namespace repose {

/// True if `text` looks like a shape spec ("name:..."), as opposed to a file name.
bool is_shape_spec(const std::string& text);

/// Builds the mesh of a built-in shape. Throws repose::Error naming the spec and the problem for an unknown
/// shape, an unknown or missing parameter, or a value that is not a finite positive number.
TriangleMesh make_shape(const std::string& spec);

}  // namespace repose
