#pragma once
// The kinetic per-pixel-square triangle sets of exact antialiasing (docs/design.md, "Exact
// antialiasing: the pixel's square as the frustum"): for every pixel, the triangles whose image
// region overlaps the pixel's closed square, kept up to date by events only. A triangle's squares
// change only when an edge line passes a square corner (E_pq at the corner, quadratic), a vertex
// crosses a pixel line (X - x Z or Y - y Z, linear), a vertex crosses the eye plane, or, for a
// triangle across the eye plane, its plane sweeps the eye (O, cubic) or an edge line turns
// horizontal (n_x, quadratic); and at a key, an appearance or a disappearance. Each triangle's
// record (triangle_footprint.h) reads the few of those that bracket it; a vertex's cells
// (vertex_cells.h) and an edge's corner steps (edge_steps.h) are followed once for all the
// triangles around them.
//
//   PixelSquareSets sets(input, t0);
//   for (double t : frame_times) { sets.advance_to(t); for each pixel: sets.triangles(i, j); }
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "kinetic/core/simulator.h"
#include "kinetic/grid/grid_input.h"
#include "kinetic/grid/grid_scene.h"
#include "kinetic/squares/edge_steps.h"
#include "kinetic/squares/square_change_log.h"
#include "kinetic/squares/square_lattice.h"
#include "kinetic/squares/square_stats.h"
#include "kinetic/squares/triangle_footprint.h"

namespace kinray {

class PixelSquareSets {
 public:
  struct Config {
    /// Audit after each advance (audit()); a problem throws KineticAuditFailure.
    bool audit = false;
  };

  /// Builds every present triangle's record at start_time. The meshes' spans must outlive this.
  PixelSquareSets(GridInput input, double start_time, const Config& config);
  PixelSquareSets(GridInput input, double start_time)
      : PixelSquareSets(std::move(input), start_time, Config{}) {}

  /// Processes every event with time <= t, in time order (t must not decrease).
  void advance_to(double t);
  [[nodiscard]] double now() const { return m_sim.now(); }

  /// The triangles whose region overlaps the closed square of pixel (i, j) (row 0 at the top),
  /// in no particular order; valid until the next advance_to.
  [[nodiscard]] std::span<const SquareTriangle> triangles(int i, int j) const {
    return m_pixels[size_t(j) * size_t(m_lattice.width()) + size_t(i)];
  }

  /// At now(), which must lie strictly between events: every live certificate has the sign its
  /// record claims, and every pixel's set is the brute force's (square_overlap.h), ties excepted.
  /// The problems found (empty: none); `ties` counts the (triangle, square) ties met.
  [[nodiscard]] std::vector<std::string> audit(size_t* ties = nullptr) const;

  /// While on, every entry into or exit from a pixel's set made by advance_to is appended to
  /// changes() with its event's time (square_change_log.h); the caller reads and clears it. Off
  /// (the default) costs one test per change.
  void log_changes(bool on) { m_logging = on; }
  [[nodiscard]] const SquareChangeLog& changes() const { return m_changes; }
  void clear_changes() { m_changes.clear(); }

  [[nodiscard]] SquareStats stats() const;
  [[nodiscard]] const SquareLattice& lattice() const { return m_lattice; }
  [[nodiscard]] const GridInput& input() const { return m_input; }
  /// Positions of mesh m's triangle `triangle` at t, as FlightplanMesh::position blends them.
  [[nodiscard]] std::array<Eigen::Vector3d, 3> triangle_at(uint32_t m, uint32_t triangle,
                                                           double t) const;

 private:
  class Audit;
  // Records (pixel_square_sets_records.cpp).
  [[nodiscard]] TriangleMotion motion(uint32_t tri) const;
  /// Global ids of tri's vertices.
  [[nodiscard]] std::array<uint32_t, 3> vertex_ids(uint32_t tri) const;
  /// The mode tri's record takes now, from its vertices' sides of the eye plane and O.
  [[nodiscard]] TriangleRecord::Mode mode_of(uint32_t tri, const TriangleMotion& tm) const;
  /// tri's record at now(), its vertices' cells copied from their trackers (followed already).
  void build(uint32_t tri, TriangleRecord& rec) const;
  /// Lays out rec's row lines and strips from its vertices' rows and locates each edge's step on
  /// each line; an entry of `old` (the same triangle's record in the same mode before a vertex
  /// changed row) with the same line and edge is taken over instead, with its pending event.
  void follow_lines(uint32_t tri, TriangleRecord& rec, const TriangleMotion& tm, double s,
                    TriangleRecord* old = nullptr) const;
  void compute_strips(TriangleRecord& rec) const;
  /// Replaces tri's record by a fresh one at now(), its pixels and events updated.
  void rebuild(uint32_t tri);
  /// tri's record after one of its vertices changed row (its mode unchanged): the lines and
  /// strips laid out again, the steps and events of the lines it keeps taken over.
  void reshape(uint32_t tri);
  /// Drops tri's record: out of its pixels, its events cancelled.
  void clear(uint32_t tri);
  /// Moves tri in or out of the pixels of strips [j0, j1) where `before` and its record differ.
  void update_pixels(uint32_t tri, const TriangleRecord& before, int j0, int j1);
  /// Recomputes tri's strips [j0, j1) from its record (after a cell or a step moved), moving it
  /// in or out of the pixels that changed.
  void refresh_strips(uint32_t tri, int j0, int j1);
  // Vertices (pixel_square_sets_vertices.cpp).
  [[nodiscard]] PointMotion vertex_motion(uint32_t v) const;
  [[nodiscard]] double vertex_local_time(uint32_t v) const {
    return m_sim.now() - m_segments[m_vertex_mesh[v]].origin;
  }
  /// Locates v's side of the eye plane, and its cells when it has users.
  void locate_vertex(uint32_t v);
  /// A record starts (follow) or stops (unfollow) reading v's cells: the first user locates
  /// them, the last one drops them; v's certificates follow.
  void follow(uint32_t v);
  void unfollow(uint32_t v);
  // Edges (pixel_square_sets_edges.cpp).
  /// The global edge ids of every triangle, and each edge's triangles.
  void index_edges();
  /// +1 when tri's edge e runs in its edge's own direction, -1 the other way.
  [[nodiscard]] int edge_direction(uint32_t tri, int e) const;
  [[nodiscard]] EdgeNormal edge_normal_of(uint32_t edge) const;
  /// Lays edge's lines out from its end points' rows, the steps of lines it keeps taken over.
  void layout_edge(uint32_t edge);
  void follow_edge(uint32_t edge);
  void unfollow_edge(uint32_t edge);
  void schedule_edge_line(uint32_t edge, size_t index, const EdgeNormal& n);
  void schedule_edge(uint32_t edge);
  void edge_corner_event(uint32_t edge, size_t index);
  /// The followed edges that have v as an end point.
  [[nodiscard]] std::vector<uint32_t> followed_edges_at(uint32_t v) const;
  void add(uint32_t tri, int i, int j);
  void remove(uint32_t tri, int i, int j);
  // Certificates (pixel_square_sets_schedule.cpp).
  [[nodiscard]] double failure_time(int sign, const Polynomial& f, uint32_t mesh) const;
  void schedule_all(uint32_t tri);
  void schedule_vertex(uint32_t v);
  // Each takes the triangle's motion on its segment (motion(tri)), computed once per event.
  void schedule_line(uint32_t tri, size_t entry, const TriangleMotion& tm);
  void schedule_orientation(uint32_t tri, const TriangleMotion& tm);
  void schedule_horizon(uint32_t tri, int edge, const TriangleMotion& tm);
  void schedule_key(uint32_t m);
  void schedule_presence(uint32_t m);
  void cancel_all(TriangleRecord& rec);
  // Events (pixel_square_sets.cpp).
  void handle(const EventKey& key, uint64_t payload);
  void vertex_event(uint32_t v);
  void corner_event(uint32_t tri, size_t entry);
  [[nodiscard]] bool moving(uint32_t tri) const {
    return !m_input.meshes[m_triangle_mesh[tri]].is_static;
  }
  [[nodiscard]] double local_time(uint32_t tri) const {
    return m_sim.now() - m_segments[m_triangle_mesh[tri]].origin;
  }

  GridInput m_input;
  SquareLattice m_lattice;
  Config m_config;
  Simulator m_sim;
  std::vector<uint32_t> m_triangle_begin;  ///< per mesh, prefix sums (global triangle ids)
  std::vector<uint32_t> m_triangle_mesh;   ///< per global triangle
  std::vector<MeshSegment> m_segments;     ///< per mesh: the key segment of now()
  std::vector<uint8_t> m_present;          ///< per mesh
  std::vector<EventHandle> m_key_events, m_presence_events;  ///< per mesh
  std::vector<TriangleRecord> m_records;                     ///< per global triangle
  std::vector<uint32_t> m_vertex_begin;   ///< per mesh, prefix sums (global vertex ids)
  std::vector<uint32_t> m_vertex_mesh;    ///< per global vertex
  std::vector<VertexTracker> m_vertices;  ///< per global vertex
  std::vector<uint32_t> m_adjacency_begin, m_adjacency;      ///< global vertex -> its triangles
  std::vector<std::array<uint32_t, 3>> m_triangle_edges;     ///< per triangle: its edges' ids
  std::vector<std::array<uint32_t, 2>> m_edge_vertices;      ///< per edge: lower id first
  std::vector<EdgeTracker> m_edges;                          ///< per edge
  std::vector<uint32_t> m_edge_triangles_begin, m_edge_triangles;  ///< edge -> its triangles
  std::vector<std::vector<SquareTriangle>> m_pixels;         ///< row-major
  SquareStats m_stats;
  bool m_logging = false;
  SquareChangeLog m_changes;
};

}  // namespace kinray
