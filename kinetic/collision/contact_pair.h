#pragma once
// The leaf-level unit of continuous collision detection: two primitives (a vertex and a
// triangle, or two edges) whose four points move linearly over one flightplan segment. Every
// contact finder (brute force, swept volumes, and the kinetic separation list) hands pairs of
// this form to the same primitive test (primitive_ccd.h).
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>

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

/// The window [begin, end] of absolute time inside the segment [segment_begin, segment_end], in
/// the segment's local time, widened by more than the rounding of the division: a wider window
/// only meets contacts that the whole segment's tests report anyway, at the same times, and the
/// caller keeps those in [begin, end] (or drops repeats).
[[nodiscard]] inline LocalWindow local_window(double segment_begin, double segment_end,
                                              double begin, double end) {
  const double length = segment_end - segment_begin;
  auto local = [&](double t, double direction) {
    const double u = (t - segment_begin) / length;
    const double error = 4 * std::numeric_limits<double>::epsilon() *
                         (std::fabs(u) + (std::fabs(t) + std::fabs(segment_begin)) / length);
    return std::clamp(u + direction * error, 0.0, 1.0);
  };
  return {begin <= segment_begin ? 0.0 : local(begin, -1),
          end >= segment_end ? 1.0 : local(end, +1)};
}

[[nodiscard]] inline const char* contact_type_name(ContactType type) {
  return type == ContactType::vertex_face ? "vf" : "ee";
}

}  // namespace kinray
