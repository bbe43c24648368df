#pragma once
// The geometric elements of AFF, each read from its keyword on into an AffShape (local
// coordinates, material not yet set): meshes `m`, polygons `p` and patches `pp`, textured
// triangles `tt`/`ttp`, animated triangle patches `tpa`, cones and cylinders `c`, spheres `s`.
// Normals that the file gives are checked and then dropped: kinray shades with the normals of
// the interpolated geometry, the same for every backend.
#include <string>

#include "scenes/aff_document.h"
#include "scenes/aff_reader.h"

namespace kinray {

/// A shape and the texture file its texture coordinates refer to (empty: none).
struct AffShapeRead {
  AffShape shape;
  std::string texture;
};

/// `m`: vertices N ..., [normals N ...], [texturecoords N NAME ...], triangles N ... (each
/// triangle: three vertex indices, then three normal and three texture-coordinate indices when
/// the mesh has them). Vertices with different texture coordinates are split.
[[nodiscard]] AffShapeRead read_mesh(AffReader& in);
/// `p N` (x y z)*N, or with `patch` `pp N` (x y z nx ny nz)*N: a convex polygon as a fan.
[[nodiscard]] AffShapeRead read_polygon(AffReader& in, bool patch);
/// `tt NAME` (x y z u v)*3, or with `patch` `ttp NAME` (x y z nx ny nz u v)*3.
[[nodiscard]] AffShapeRead read_textured_triangle(AffReader& in, bool patch);
/// `tpa N` then N times (time, (x y z nx ny nz)*3): a triangle moving linearly between its keys.
[[nodiscard]] AffShapeRead read_animated_triangle(AffReader& in);
/// `c` bx by bz br ax ay az ar: a cone or cylinder side (negative radii: seen from inside).
[[nodiscard]] AffShapeRead read_cone(AffReader& in);
/// `s` cx cy cz r.
[[nodiscard]] AffShapeRead read_sphere(AffReader& in);

}  // namespace kinray
