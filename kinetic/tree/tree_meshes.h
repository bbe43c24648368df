#pragma once
// The input of the kinetic trees, indexed: the triangles of camera-space meshes with
// piecewise-linear flightplans (kinetic/motion/flightplan_mesh.h's FlightplanMesh), with global
// triangle and vertex ids, and every vertex's motion on its mesh's current flightplan segment, x(t)
// = a + b (t - o). The certificates of the trees are linear in t on a segment (docs/design.md,
// "Kinetic AABB tree and kinetic BoxTree"), and every comparison of two vertices builds the same
// polynomial from these motions, so an event sees the sign change its failure time was computed
// for.
#include <Eigen/Core>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include "kinetic/core/root_finding.h"
#include "kinetic/motion/flightplan_mesh.h"

namespace kinray {

inline constexpr uint32_t kNoVertex = ~0u;
inline constexpr double kInfinityTime = std::numeric_limits<double>::infinity();

/// A linear certificate c0 + c1 s > 0 in the local time s = t - origin, valid until `end`.
struct LinearCertificate {
  double origin = 0, c0 = 0, c1 = 0;
  double end = std::numeric_limits<double>::infinity();
  /// Sign (-1, 0, +1) just after t, as root_finding.h's sign_after evaluates c0 + c1 s.
  [[nodiscard]] int sign_after(double t) const {
    const double v = c0 + c1 * (t - origin);
    if (v != 0) return v > 0 ? 1 : -1;
    return c1 > 0 ? 1 : (c1 < 0 ? -1 : 0);
  }
  /// The exact negation: the same comparison seen from the other vertex.
  [[nodiscard]] LinearCertificate negated() const { return {origin, -c0, -c1, end}; }
  /// Absolute time of the first failure after `now` (+inf when it holds until `end`). Inline is
  /// the common case, a certificate that holds through its segment (linear_holds_through).
  [[nodiscard]] double failure_time(double now) const {
    if (linear_holds_through(c0, c1, now - origin, end - origin))
      return std::numeric_limits<double>::infinity();
    // Identically zero (two vertices moving together on the axis: a flat cloth's sides): never
    // negative, as the slow path finds at the cost of a root search.
    if (c0 == 0 && c1 == 0) return std::numeric_limits<double>::infinity();
    return failure_time_slow(now);
  }
  [[nodiscard]] double failure_time_slow(double now) const;
};

class TreeMeshes {
 public:
  /// The spans of `meshes` must outlive this object. Throws std::invalid_argument on malformed
  /// meshes (key times not increasing, positions not keys x vertices, indices out of range).
  explicit TreeMeshes(std::vector<FlightplanMesh> meshes, double t);

  [[nodiscard]] uint32_t mesh_count() const { return uint32_t(m_meshes.size()); }
  [[nodiscard]] const FlightplanMesh& mesh(uint32_t m) const { return m_meshes[m]; }
  [[nodiscard]] uint32_t triangle_count() const { return uint32_t(m_triangle_vertices.size()); }
  [[nodiscard]] uint32_t vertex_count() const { return uint32_t(m_a.size()); }
  [[nodiscard]] uint32_t triangle_begin(uint32_t m) const { return m_triangle_begin[m]; }
  [[nodiscard]] uint32_t triangle_end(uint32_t m) const { return m_triangle_begin[m + 1]; }
  [[nodiscard]] uint32_t mesh_of_triangle(uint32_t tri) const { return m_triangle_mesh[tri]; }
  [[nodiscard]] uint32_t mesh_of_vertex(uint32_t v) const { return m_vertex_mesh[v]; }
  /// Global vertex ids of a global triangle.
  [[nodiscard]] const std::array<uint32_t, 3>& triangle(uint32_t tri) const {
    return m_triangle_vertices[tri];
  }
  /// The global id of a mesh's triangle, and back.
  [[nodiscard]] uint32_t local_triangle(uint32_t tri) const {
    return tri - m_triangle_begin[m_triangle_mesh[tri]];
  }
  [[nodiscard]] bool present(uint32_t m) const { return m_present[m] != 0; }
  /// The largest |coordinate| of any key position: the scale of the rounding between a segment's
  /// a + b (t - o) and a key blend, which the queries pad their boxes by.
  [[nodiscard]] double scale() const { return m_scale; }
  /// Lowest and highest coordinates of any key position: a box around every vertex at every
  /// time (the motion between keys is linear), without events.
  [[nodiscard]] const Eigen::Vector3d& shot_lo() const { return m_shot_lo; }
  [[nodiscard]] const Eigen::Vector3d& shot_hi() const { return m_shot_hi; }

  /// Moves mesh m onto the flightplan segment active just after t and sets its presence at t.
  void set_time(uint32_t m, double t);
  /// The next time after t at which mesh m changes segment, appears or disappears (+inf: never).
  [[nodiscard]] double next_change(uint32_t m, double t) const;
  /// Where the current segment of mesh m ends (the next flightplan update).
  [[nodiscard]] double segment_end(uint32_t m) const { return m_segment_end[m]; }
  /// The segment motion does not move (a static mesh, or before the first / after the last key).
  [[nodiscard]] bool still(uint32_t m) const { return m_still[m] != 0; }

  /// Coordinate `axis` of vertex v at t on its current segment: a + b (t - o). The kinetic trees'
  /// boxes; within a few ulps of FlightplanMesh::position (a key blend), which the queries pad for.
  [[nodiscard]] double coordinate(uint32_t v, int axis, double t) const {
    return m_a[v][axis] + m_b[v][axis] * (t - m_origin[m_vertex_mesh[v]]);
  }
  /// Coordinate `axis` of vertex v's velocity on its current segment (b of a + b (t - o)): the
  /// slope of a certificate between vertices of two different trees.
  [[nodiscard]] double velocity(uint32_t v, int axis) const { return m_b[v][axis]; }
  /// Mesh m's vertices are [vertex_begin(m), vertex_begin(m + 1)), and its current segment's
  /// motions a + b (t - o) share o = segment_origin(m): a pass over every vertex at one t
  /// (FrameBoxes) computes t - o once per mesh, with the same arithmetic as coordinate().
  [[nodiscard]] uint32_t vertex_begin(uint32_t m) const { return m_vertex_begin[m]; }
  [[nodiscard]] double segment_origin(uint32_t m) const { return m_origin[m]; }
  [[nodiscard]] const Eigen::Vector3d& velocity(uint32_t v) const { return m_b[v]; }
  /// The certificate "vertex r is beyond vertex q along axis, on side sign (+1 max, -1 min)":
  /// sign (x_r - x_q) as a linear polynomial. Built in one order (lower vertex id first) and
  /// negated exactly for the other, so the two vertices' comparison has one set of coefficients.
  [[nodiscard]] LinearCertificate beyond(uint32_t r, uint32_t q, int axis, int sign) const;
  /// r realizes the side rather than q just after t (ties in the whole motion: the lower id).
  [[nodiscard]] bool beats(uint32_t r, uint32_t q, int axis, int sign, double t) const {
    const int s = beyond(r, q, axis, sign).sign_after(t);
    return s > 0 || (s == 0 && r < q);
  }

  /// Decides "r stays beyond q through the current segment" from the positions at its two keys
  /// alone (the motion is linear in between): both vertices of one moving mesh, r beyond q by
  /// more than `margin` at both keys. False means "not decided this way", not "fails".
  [[nodiscard]] bool beyond_at_both_keys(uint32_t r, uint32_t q, int axis, int sign,
                                         double margin) const {
    const uint32_t m = m_vertex_mesh[r];
    if (m_vertex_mesh[q] != m || m_still[m]) return false;
    return sign * (m_a[r][axis] - m_a[q][axis]) > margin &&  // a is the key position at the origin
           sign * (m_end[r][axis] - m_end[q][axis]) > margin;
  }
  /// r and q (of one moving mesh) have the same coordinate on the axis at both keys: they move
  /// together there, their certificate is identically zero and the lower id realizes the side
  /// (a flat region's sides, which no margin settles).
  [[nodiscard]] bool tied_at_both_keys(uint32_t r, uint32_t q, int axis) const;
  /// Vertex v's positions at the two keys of its mesh's current segment (equal when still): what
  /// the key pass of the trees compares (kinetic_bvh_keys.cpp).
  [[nodiscard]] const Eigen::Vector3d& key_start(uint32_t v) const { return m_a[v]; }
  [[nodiscard]] const Eigen::Vector3d& key_end(uint32_t v) const { return m_end[v]; }

  /// The key blend of every mesh at t, for exact positions (FlightplanMesh::position) in queries.
  void blends_at(double t, std::vector<FlightplanMesh::KeyBlend>& out) const;
  /// Vertex v's position as FlightplanMesh::position computes it (the Embree reference's
  /// arithmetic).
  [[nodiscard]] Eigen::Vector3d position(
      uint32_t v, const std::vector<FlightplanMesh::KeyBlend>& blends) const {
    const uint32_t m = m_vertex_mesh[v];
    return m_meshes[m].position(v - m_vertex_begin[m], blends[m]);
  }

 private:
  std::vector<FlightplanMesh> m_meshes;
  std::vector<uint32_t> m_triangle_begin, m_vertex_begin, m_triangle_mesh, m_vertex_mesh;
  std::vector<std::array<uint32_t, 3>> m_triangle_vertices;
  std::vector<Eigen::Vector3d> m_a, m_b;           ///< per vertex, on the mesh's current segment
  std::vector<Eigen::Vector3d> m_end;              ///< per vertex: the key ending the segment
  std::vector<double> m_origin, m_segment_end;     ///< per mesh
  std::vector<uint8_t> m_present, m_still;         ///< per mesh
  double m_scale = 0;
  Eigen::Vector3d m_shot_lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector3d m_shot_hi = Eigen::Vector3d::Constant(-std::numeric_limits<double>::infinity());
};

}  // namespace kinray
