#pragma once
// Rest-pose meshes that the procedural scenes and the primitives of scene files start from.
// Every builder shares vertices along edges (watertight meshes: a kinetic boundary never sees a
// crack between two triangles of one object) and orients triangles counter-clockwise seen from
// outside in the right-handed world.
#include <Eigen/Geometry>
#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "scenes/scene.h"

namespace kinray {

/// A triangle mesh in its rest pose.
struct Mesh {
  std::vector<Vec3> positions;
  std::vector<Triangle> triangles;
  std::vector<Vec2f> uvs;  ///< per vertex, or empty
};

/// Subdivisions n of a cube sphere or box (12 n^2 triangles) closest to `triangles`, at least 1.
[[nodiscard]] int cube_subdivisions_for(double triangles);

/// A sphere of `radius` around the origin, tessellated as a cube whose faces are n x n quads
/// projected onto the sphere with equal-angle spacing: 12 n^2 triangles of nearly equal size,
/// no poles and no seam.
[[nodiscard]] Mesh make_sphere(double radius, int subdivisions);

/// An axis-aligned box of the given edge lengths centred at the origin, n x n quads per face.
[[nodiscard]] Mesh make_box(const Vec3& size, int subdivisions);

/// A rectangle in the xz-plane centred at the origin, facing +y, with nx x nz quads and uvs
/// (u along +x, v along +z, both in [0, 1]).
[[nodiscard]] Mesh make_grid(double size_x, double size_z, int nx, int nz);

/// Applies `transform` to every position of `mesh`, into `out` (resized).
void transform_positions(const Mesh& mesh, const Eigen::Affine3d& transform,
                         std::vector<Vec3>& out);

/// A static object (one key at time 0): `mesh` placed by `transform`.
[[nodiscard]] Object make_static_object(
    std::string name, const Mesh& mesh, uint32_t material,
    const Eigen::Affine3d& transform = Eigen::Affine3d::Identity());

/// Writes the positions of every vertex at time t into `out` (already sized to the vertex count).
using PoseFunction = std::function<void(double t, std::vector<Vec3>& out)>;

/// An object with `mesh`'s triangles and uvs whose key positions at each of `times` come from
/// `pose` (called in parallel for different keys, so it must be thread-safe).
[[nodiscard]] Object make_keyframed_object(std::string name, const Mesh& mesh, uint32_t material,
                                           const std::vector<double>& times,
                                           const PoseFunction& pose);

/// A rigid motion: `mesh` placed by `transform(t)` at each of `times`.
[[nodiscard]] Object make_rigid_object(std::string name, const Mesh& mesh, uint32_t material,
                                       const std::vector<double>& times,
                                       const std::function<Eigen::Affine3d(double t)>& transform);

}  // namespace kinray
