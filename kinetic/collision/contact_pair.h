#pragma once
// The leaf-level unit of continuous collision detection: two primitives (a vertex and a
// triangle, or two edges) whose four points move linearly over one flightplan segment. Every
// contact finder (brute force, swept volumes, and the kinetic separation list) hands pairs of
// this form to the same primitive test (primitive_ccd.h).
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <cstdint>

namespace kinray {

/// Which primitives touch.
enum class ContactType : std::uint8_t {
  vertex_face,  ///< points: v, f0, f1, f2
  edge_edge,    ///< points: a0, a1, b0, b1
};

/// Four points moving linearly from `start` (local time 0) to `end` (local time 1).
struct PrimitiveMotion {
  std::array<Eigen::Vector3d, 4> start{};
  std::array<Eigen::Vector3d, 4> end{};

  /// The four points at local time t in [0, 1].
  [[nodiscard]] std::array<Eigen::Vector3d, 4> at(double t) const {
    std::array<Eigen::Vector3d, 4> p;
    for (int i = 0; i < 4; ++i) p[i] = start[i] + t * (end[i] - start[i]);
    return p;
  }
};

[[nodiscard]] inline const char* contact_type_name(ContactType type) {
  return type == ContactType::vertex_face ? "vf" : "ee";
}

}  // namespace kinray
