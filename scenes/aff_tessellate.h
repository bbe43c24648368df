#pragma once
// Triangles for the curved primitives of NFF/AFF, which kinray (a triangle ray tracer) needs as
// meshes: cones and cylinders (the open side surface, no end caps, as NFF defines them) and
// spheres. The level is fixed and documented (docs/bart.md): kConeSegments around every cone, a
// sphere of kSphereRings rings of kSphereSegments quads (two triangles each, fans at the poles).
#include <vector>

#include "scenes/scene.h"

namespace kinray {

inline constexpr int kConeSegments = 32;
inline constexpr int kSphereSegments = 32;
inline constexpr int kSphereRings = 16;

/// A triangulated mesh: positions and triangles, counter-clockwise seen from outside.
struct TriangleMesh {
  std::vector<Vec3> positions;
  std::vector<Triangle> triangles;
};

/// The side of a cone from `base` (radius base_radius) to `apex` (radius apex_radius; equal radii
/// make a cylinder). Radii must be >= 0 and not both 0, base != apex (the parser checks).
[[nodiscard]] TriangleMesh tessellate_cone(const Vec3& base, double base_radius, const Vec3& apex,
                                           double apex_radius);
/// A sphere of `radius` > 0 around `center`.
[[nodiscard]] TriangleMesh tessellate_sphere(const Vec3& center, double radius);
/// A convex polygon's vertices as a fan from vertex 0 (BART's parsePoly).
[[nodiscard]] std::vector<Triangle> fan_triangles(size_t vertex_count);

}  // namespace kinray
