#pragma once
// A triangle mesh whose vertices move on piecewise-linear camera-space flightplans: what the
// kinetic grid, the kinetic trees and collision detection take as input. Positions are blended
// exactly as scenes/camera_space.h's CameraSpaceObject::position blends them, so that every
// consumer and the references see bit-identical vertices.
#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <span>
#include <stdexcept>
#include <string>

#include <Eigen/Core>

namespace kinray {

/// One triangle mesh as camera-space flightplans: every vertex moves linearly between the shared
/// key times and stands still before the first and after the last. The spans point into the
/// caller's data, which must outlive the grid.
struct FlightplanMesh {
  uint32_t id = 0;                               ///< reported by the read-out (the object index)
  std::span<const double> key_times;             ///< strictly increasing, at least one
  std::span<const Eigen::Vector3d> positions;    ///< [key * vertex_count + v]
  size_t vertex_count = 0;
  std::span<const std::array<uint32_t, 3>> triangles;
  double appear = -std::numeric_limits<double>::infinity();  ///< present on [appear, disappear)
  double disappear = std::numeric_limits<double>::infinity();
  bool is_static = false;  ///< positions equal at every key: emits no coverage events

  [[nodiscard]] size_t key_count() const { return key_times.size(); }
  [[nodiscard]] bool present(double t) const { return t >= appear && t < disappear; }
  [[nodiscard]] const Eigen::Vector3d& key_position(size_t key, uint32_t v) const {
    return positions[key * vertex_count + v];
  }
  /// Where t falls on the key grid: between keys k and k + 1 at fraction alpha, or `still` at key
  /// 0 (before the first key, or a single key).
  struct KeyBlend {
    size_t k = 0;
    double alpha = 0;
    bool still = true;
  };
  [[nodiscard]] KeyBlend blend_at(double t) const {
    const size_t n = key_times.size();
    if (n < 2 || t <= key_times[0]) return {};
    KeyBlend b{n - 2, 1.0, false};
    if (t < key_times[n - 1]) {
      b.k = size_t(std::upper_bound(key_times.begin(), key_times.end(), t) - key_times.begin()) - 1;
      b.alpha = (t - key_times[b.k]) / (key_times[b.k + 1] - key_times[b.k]);
    }
    return b;
  }
  /// Position of vertex v at a blend: exactly CameraSpaceObject::position's arithmetic (one blend
  /// serves every vertex at one time).
  [[nodiscard]] Eigen::Vector3d position(uint32_t v, const KeyBlend& b) const {
    const Eigen::Vector3d& a = positions[b.k * vertex_count + v];
    if (b.still) return a;
    const Eigen::Vector3d& c = positions[(b.k + 1) * vertex_count + v];
    return a + b.alpha * (c - a);
  }
  /// Position of vertex v at t.
  [[nodiscard]] Eigen::Vector3d position(uint32_t v, double t) const {
    return position(v, blend_at(t));
  }
};

/// Throws std::invalid_argument (message prefixed by `where`) unless the mesh is well formed: key
/// times present and strictly increasing, positions keys x vertices, vertex indices in range.
inline void validate_mesh(const FlightplanMesh& mesh, const std::string& where) {
  if (mesh.key_times.empty()) throw std::invalid_argument(where + "no key times");
  for (size_t k = 1; k < mesh.key_times.size(); ++k)
    if (!(mesh.key_times[k] > mesh.key_times[k - 1]))
      throw std::invalid_argument(where + "key times not strictly increasing");
  if (mesh.positions.size() != mesh.key_times.size() * mesh.vertex_count)
    throw std::invalid_argument(where + "positions do not match keys x vertices");
  for (const auto& tri : mesh.triangles)
    for (uint32_t v : tri)
      if (v >= mesh.vertex_count) throw std::invalid_argument(where + "vertex index out of range");
}

}  // namespace kinray
