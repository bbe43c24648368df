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

  /// The four points at local time t in [0, 1]; exactly `end` at 1, where the next segment
  /// starts from the same positions (a contact met at both has one point).
  [[nodiscard]] std::array<Eigen::Vector3d, 4> at(double t) const {
    if (t == 1) return end;
    std::array<Eigen::Vector3d, 4> p;
    for (int i = 0; i < 4; ++i) p[i] = start[i] + t * (end[i] - start[i]);
    return p;
  }
};

/// A closed window [lo, hi] of local time, 0 <= lo <= hi <= 1: the primitive tests report the
/// contacts whose exact time lies in it, at the times a test over all of [0, 1] reports them
/// (rounded down to the same grid, anchored at local time 0).
struct LocalWindow {
  double lo = 0, hi = 1;
  [[nodiscard]] bool whole() const { return lo == 0 && hi == 1; }
  [[nodiscard]] bool contains(double t) const { return lo <= t && t <= hi; }
};

[[nodiscard]] inline const char* contact_type_name(ContactType type) {
  return type == ContactType::vertex_face ? "vf" : "ee";
}

}  // namespace kinray
