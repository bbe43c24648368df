#include "scenes/mesh_builders.h"

#include <algorithm>
#include <cmath>
#include <unordered_map>

#include "util/parallel.h"

namespace kinray {

namespace {

/// The surface of the integer lattice cube [0, n]^3, n x n quads per face, vertices shared along
/// edges and corners (found by their integer coordinates, so sharing is exact). `place` maps a
/// lattice point in [-1, 1]^3 to its position.
template <class Place>
Mesh make_cube_lattice(int n, Place&& place) {
  // Faces as (normal axis, sign, u axis, v axis) with u x v = outward normal, so that the quads
  // (a, b) -> (a+1, b) -> (a+1, b+1) are counter-clockwise seen from outside.
  struct Face {
    int axis, u, v;
    bool positive;
  };
  static constexpr Face kFaces[6] = {{0, 1, 2, true},  {0, 2, 1, false}, {1, 2, 0, true},
                                     {1, 0, 2, false}, {2, 0, 1, true},  {2, 1, 0, false}};
  Mesh mesh;
  const size_t side = size_t(n) + 1;
  mesh.positions.reserve(6 * size_t(n) * size_t(n) + 2);
  mesh.triangles.reserve(12 * size_t(n) * size_t(n));
  std::unordered_map<uint64_t, uint32_t> shared;  // lattice key -> vertex, for face borders only
  std::vector<uint32_t> face_index(side * side);
  for (const Face& face : kFaces) {
    for (int b = 0; b <= n; ++b)
      for (int a = 0; a <= n; ++a) {
        int lattice[3];
        lattice[face.axis] = face.positive ? n : 0;
        lattice[face.u] = a;
        lattice[face.v] = b;
        const bool border = a == 0 || a == n || b == 0 || b == n;
        const uint64_t key =
            (uint64_t(lattice[0]) * side + uint64_t(lattice[1])) * side + uint64_t(lattice[2]);
        uint32_t index = uint32_t(mesh.positions.size());
        if (border) {
          const auto [it, inserted] = shared.emplace(key, index);
          if (!inserted) {
            face_index[size_t(b) * side + size_t(a)] = it->second;
            continue;
          }
        }
        face_index[size_t(b) * side + size_t(a)] = index;
        const Vec3 unit(2.0 * lattice[0] / n - 1.0, 2.0 * lattice[1] / n - 1.0,
                        2.0 * lattice[2] / n - 1.0);
        mesh.positions.push_back(place(unit));
      }
    for (int b = 0; b < n; ++b)
      for (int a = 0; a < n; ++a) {
        const uint32_t v00 = face_index[size_t(b) * side + size_t(a)];
        const uint32_t v10 = face_index[size_t(b) * side + size_t(a + 1)];
        const uint32_t v11 = face_index[size_t(b + 1) * side + size_t(a + 1)];
        const uint32_t v01 = face_index[size_t(b + 1) * side + size_t(a)];
        mesh.triangles.push_back({v00, v10, v11});
        mesh.triangles.push_back({v00, v11, v01});
      }
  }
  return mesh;
}

}  // namespace

int cube_subdivisions_for(double triangles) {
  if (!(triangles > 12)) return 1;
  return std::max(1, int(std::lround(std::sqrt(triangles / 12.0))));
}

Mesh make_sphere(double radius, int subdivisions) {
  return make_cube_lattice(std::max(1, subdivisions), [radius](const Vec3& c) {
    // Equal-angle warp: lattice lines become great circles at equal angles, so triangles near the
    // cube's corners are not much smaller than those at the face centres.
    const Vec3 warped(std::tan(c.x() * M_PI / 4), std::tan(c.y() * M_PI / 4),
                      std::tan(c.z() * M_PI / 4));
    return Vec3(radius * warped.normalized());
  });
}

Mesh make_box(const Vec3& size, int subdivisions) {
  return make_cube_lattice(std::max(1, subdivisions), [half = Vec3(0.5 * size)](const Vec3& c) {
    return Vec3(c.cwiseProduct(half));
  });
}

Mesh make_grid(double size_x, double size_z, int nx, int nz) {
  nx = std::max(1, nx);
  nz = std::max(1, nz);
  Mesh mesh;
  const size_t row = size_t(nx) + 1;
  mesh.positions.reserve(row * (size_t(nz) + 1));
  mesh.uvs.reserve(mesh.positions.capacity());
  for (int j = 0; j <= nz; ++j)
    for (int i = 0; i <= nx; ++i) {
      const double u = double(i) / nx, v = double(j) / nz;
      mesh.positions.emplace_back((u - 0.5) * size_x, 0.0, (v - 0.5) * size_z);
      mesh.uvs.emplace_back(float(u), float(v));
    }
  mesh.triangles.reserve(2 * size_t(nx) * size_t(nz));
  for (int j = 0; j < nz; ++j)
    for (int i = 0; i < nx; ++i) {
      const uint32_t v00 = uint32_t(size_t(j) * row + size_t(i));
      const uint32_t v10 = v00 + 1, v01 = v00 + uint32_t(row), v11 = v01 + 1;
      // z x x = +y: walking +z then +x is counter-clockwise seen from above.
      mesh.triangles.push_back({v00, v01, v11});
      mesh.triangles.push_back({v00, v11, v10});
    }
  return mesh;
}

void transform_positions(const Mesh& mesh, const Eigen::Affine3d& transform,
                         std::vector<Vec3>& out) {
  out.resize(mesh.positions.size());
  for (size_t v = 0; v < out.size(); ++v) out[v] = transform * mesh.positions[v];
}

Object make_static_object(std::string name, const Mesh& mesh, uint32_t material,
                          const Eigen::Affine3d& transform) {
  Object object;
  object.name = std::move(name);
  object.triangles = mesh.triangles;
  object.uvs = mesh.uvs;
  object.material = material;
  object.key_times = {0.0};
  object.key_positions.resize(1);
  transform_positions(mesh, transform, object.key_positions[0]);
  return object;
}

Object make_keyframed_object(std::string name, const Mesh& mesh, uint32_t material,
                             const std::vector<double>& times, const PoseFunction& pose) {
  Object object;
  object.name = std::move(name);
  object.triangles = mesh.triangles;
  object.uvs = mesh.uvs;
  object.material = material;
  object.key_times = times;
  object.key_positions.assign(times.size(), std::vector<Vec3>(mesh.positions.size()));
  parallel_for(times.size(), 0, [&](size_t k) { pose(times[k], object.key_positions[k]); });
  return object;
}

Object make_rigid_object(std::string name, const Mesh& mesh, uint32_t material,
                         const std::vector<double>& times,
                         const std::function<Eigen::Affine3d(double t)>& transform) {
  return make_keyframed_object(
      std::move(name), mesh, material, times,
      [&](double t, std::vector<Vec3>& out) { transform_positions(mesh, transform(t), out); });
}

}  // namespace kinray
