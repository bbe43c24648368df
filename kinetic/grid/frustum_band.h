#pragma once
// One band of rows of the kinetic grid of frusta, simulated on its own event queue (docs/design.md,
// "Coverage", "Depth order per pixel", "Bands and the frame loop"). A band owns
//   - the (triangle, row) records of its rows, each with the interval of columns it covers and
//     two boundaries, the points where two of its edges meet the row plane,
//   - the (edge, row) boundaries, each on a slot of the column circle (boundary events) and
//     shared by the two triangles of its edge,
//   - a row slot per vertex among its own row planes (vertex-row events; a vertex outside the
//     band sits in the band's off slot),
//   - one orientation certificate per triangle that has records in the band,
//   - one kinetic depth order per pixel of its rows (swap events),
//   - the flightplan segment each mesh is on, switched by flightplan update events, and the
//     insert / delete events of meshes that appear and disappear.
// Rows depend on nothing outside their band, so bands run in parallel and the frames do not
// depend on how the rows are split. See docs/kinetic_grid.md.
//
// The member functions are defined by part, one file each: frustum_band_events.cpp (event loop),
// _geometry (motion just after now), _schedule (failure times), _records, _boundaries,
// _vertex_rows, _orientation (orientation and the culling watch), _meshes (insert, remove,
// flightplan switch), _audit and _readout.
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "kinetic/core/event_queue.h"
#include "kinetic/core/simulator.h"
#include "kinetic/grid/band_motion.h"
#include "kinetic/grid/coverage_rule.h"
#include "kinetic/grid/front_change_log.h"
#include "kinetic/grid/grid_scene.h"
#include "kinetic/grid/grid_stats.h"
#include "kinetic/grid/pixel_orders.h"
#include "kinetic/grid/row_record.h"
#include "kinetic/sort/depth_sort_kind.h"
#include "kinetic/sort/kinetic_sort.h"
#include "util/work_progress.h"

namespace kinray {

struct FrustumBandTestAccess;

/// EventKey::kind of the grid's events; at equal times they are processed in this order, so a
/// flightplan update (which recomputes certificates) precedes the failures computed on the old
/// segment that end there.
enum GridEventKind : uint32_t {
  kGridFlightplan = 0,
  kGridRemove = 1,
  kGridInsert = 2,
  kGridOrientation = 3,
  kGridVertexRow = 4,
  kGridBoundary = 5,
  kGridSwap = 6,
};

class FrustumBand {
 public:
  struct Config {
    DepthSortKind sort = DepthSortKind::kList;  ///< the pixel orders' kinetic sort
    bool audit = false;          ///< audit each touched pixel order after every change
    bool counts_meshes = false;  ///< counts the per-mesh events (exactly one band does)
    WorkProgress* init_progress = nullptr;  ///< start() counts the triangles it scans here
  };

  /// Rows [row_begin, row_end) of `scene`, which must outlive the band. Nothing is built yet.
  FrustumBand(const GridScene& scene, int row_begin, int row_end, const Config& config);
  FrustumBand(const FrustumBand&) = delete;
  FrustumBand& operator=(const FrustumBand&) = delete;

  /// Initialisation at t0 by scan conversion: every mesh present at t0 is inserted, later
  /// appearances and disappearances and flightplan updates are scheduled.
  void start(double t0);
  /// Processes every event with time <= t in (time, kind, ids) order.
  void advance_to(double t);

  /// The front triangle (global id) of pixel (column, row) of this band.
  [[nodiscard]] std::optional<uint32_t> front(int column, int row) const {
    const uint32_t tri = m_fronts[pixel_index(column, row)];
    return tri == kNoFront ? std::nullopt : std::optional<uint32_t>(tri);
  }
  /// The front triangles of row `row` of this band (kNoFront where empty), one per column: the
  /// read-out copies them without visiting the pixel orders.
  [[nodiscard]] const uint32_t* front_row(int row) const {
    return m_fronts.data() + pixel_index(0, row);
  }
  /// Every triangle (global id) of pixel (column, row)'s depth order into `out` (cleared
  /// first): front to back for the sorted list, the front first but otherwise unsorted for the
  /// tournament and the heap.
  void members(int column, int row, std::vector<uint32_t>& out) const {
    m_orders->members(pixel_index(column, row), out);
  }
  /// The number of triangles in pixel (column, row)'s depth order.
  [[nodiscard]] size_t depth_complexity(int column, int row) const {
    return m_orders->size(pixel_index(column, row));
  }
  /// Brute-force check of every invariant just after t (t >= the last event, before the next):
  /// records and their ties, slots and covered intervals against the sign rule, the rows each
  /// triangle meets, vertex slots, orientation signs, each pixel's set of triangles, and every
  /// pixel order's own audit. Returns the problems found (at most `limit`), each naming the band,
  /// t, the invariant and where (triangle and row, edge, vertex or pixel); never aborts.
  [[nodiscard]] std::vector<std::string> audit(double t, size_t limit = 20) const;
  [[nodiscard]] GridStats stats() const;
  /// stats().events.total(), without the rest.
  [[nodiscard]] uint64_t event_total() const { return m_stats.events.total(); }
  /// Motion blur: appends every later change of a pixel's front to `log` (nullptr: none).
  void set_front_log(FrontChangeLog* log) { m_front_log = log; }

 private:
  struct TriangleState {
    uint32_t head = kNoRecord;  ///< first record of the triangle in this band
    /// Sign of O just after the last update; kept while the triangle has records, and while
    /// `watched` with back-face culling.
    int8_t orientation = 0;
    /// Back-face culling: the triangle meets the band's rows (its vertices' row slots differ on
    /// some row plane), so its orientation decides whether it has records there. Elsewhere it has
    /// none whichever way it faces, and its orientation is not kept.
    bool watched = false;
    EventHandle event = kNoEvent;
  };
  struct MeshState {
    bool present = false;
    EventHandle flightplan = kNoEvent, insert = kNoEvent, remove = kNoEvent;
  };
  /// A triangle's motion on its mesh's current segment and the local time of now.
  struct TriangleNow {
    TriangleMotion motion;
    MeshSegment segment;
    double s = 0;
    bool moving = true;
  };
  /// An edge's motion (p to q, its own direction) on its mesh's current segment, and now. The
  /// end points are BandMotion's (not copies: an event reads them once if at all), valid until
  /// the mesh's next flightplan update.
  struct EdgeNow {
    const PointMotion* p = nullptr;
    const PointMotion* q = nullptr;
    MeshSegment segment;
    double s = 0;
    bool moving = true;
    uint32_t edge = 0;  ///< global edge id
    /// Built afresh (the audit's independent check); the events read BandMotion's cache.
    [[nodiscard]] EdgeNormal normal() const { return edge_normal(*p, *q); }
  };
  /// A vertex's slot among the band's row planes, as a step pattern of row sides.
  struct RowPattern {
    int slot = 0;
    int sign_lo = 1, sign_hi = 1;
    [[nodiscard]] int sign(int q) const { return q < slot ? sign_lo : sign_hi; }
  };

  // Geometry just after now.
  [[nodiscard]] TriangleNow triangle_now(uint32_t tri) const;
  [[nodiscard]] EdgeNow edge_now(uint32_t edge) const;
  [[nodiscard]] PointMotion vertex_now(uint32_t v, double& s) const;
  [[nodiscard]] RowPattern locate_vertex(const PointMotion& p, double s) const;
  void locate_boundary(EdgeBoundary& b, const EdgeNow& en) const;
  /// Puts a new boundary in the slot of `hint`, the boundary of another edge of a triangle at the
  /// same point (a vertex on the row plane), if its signs there agree; false if they do not.
  bool place_boundary(EdgeBoundary& b, const EdgeNow& en, const SlotTracker& hint) const;
  /// F > 0 (perturbed) iff the edge's point on row plane `row` is in front of the eye.
  [[nodiscard]] Polynomial boundary_front(const EdgeNow& en, int row) const;
  /// sign_plus(boundary_front(en, row), en.s), without the polynomials (boundary_front_sign).
  [[nodiscard]] int front_sign(const EdgeNow& en, int row) const;
  /// Starts fetching what covers_now reads of a record: its triangle's state, vertices and edges
  /// (as a boundary event pops), then (as it starts, once those have come) the normals of the
  /// records' other edges.
  void prefetch_coverage(const RowRecord& r) const;
  void prefetch_other_normals(uint32_t boundary) const;
  /// +1 if edge e of tri runs in its edge's own direction, else -1 (its edge function negated).
  [[nodiscard]] int edge_direction(uint32_t tri, int e) const {
    const auto& vs = m_scene.triangle_vertices(tri);
    return vs[size_t(kEdgeStart[e])] < vs[size_t(kEdgeEnd[e])] ? 1 : -1;
  }
  /// The sign of edge e of tri's function at (x, y) just after s, from the band's cached edge
  /// normals: CoverageRule's edge sign of the triangle's motion, bit for bit.
  [[nodiscard]] int cached_edge_sign(uint32_t tri, int e, double x, double y, double s) const {
    const EdgeNormal& n = m_motion.edge_normal(m_scene.edge_of_triangle(tri, e));
    return edge_direction(tri, e) > 0 ? edge_sign(n, x, y, s) : reversed_edge_sign(n, x, y, s);
  }
  [[nodiscard]] std::array<int, 3> row_sides(const TriangleNow& tn, int row) const;
  /// Scans a record's covered interval: from its boundary slots (`full` = every column).
  /// `covers(x, y)` is the sign rule in the record's row (CoverageRule::covers_in_row for its two
  /// edges), `orientation` the sign of O it holds with.
  template <class Covers>
  [[nodiscard]] std::pair<int, int> scan_coverage(const RowRecord& r, int orientation,
                                                  Covers&& covers, bool full);

  // Scheduling.
  [[nodiscard]] double failure_time(int sign, const Polynomial& f, const MeshSegment& seg) const;
  /// failure_time(sign, n.perturbed(r.x, y), seg), from r's coefficients of along(r.x, y),
  /// building the polynomial only when they vanish: the certificates of a boundary's watched
  /// columns.
  [[nodiscard]] double edge_failure_time(int sign, const EdgeNormal& n, const EdgeOnRay& r, double y,
                                         const MeshSegment& seg) const;
  /// Schedules the boundary's event; `rays`, if given, are its edge function along the two
  /// columns its slot watches (lo, hi), computed by the event; otherwise they are computed here.
  void schedule_boundary(uint32_t id, const EdgeNow& en, const EdgeNormal* edge = nullptr,
                         const std::array<EdgeOnRay, 2>* rays = nullptr);
  void schedule_vertex(uint32_t v);
  void schedule_orientation(uint32_t tri, const TriangleNow& tn);
  void schedule_flightplan(uint32_t m);

  // Records.
  uint32_t create_record(uint32_t tri, int row, int edge_a, int edge_b, const TriangleNow& tn);
  void kill_record(uint32_t rec);
  /// Ties the record's boundaries to the edges that cross its row now, then rescans it.
  void rebuild_record(uint32_t rec, const TriangleNow& tn, bool full);
  /// Recomputes the record's covered interval (from its boundary slots, or every column).
  void rescan_record(uint32_t rec, const TriangleNow& tn, bool full);
  /// Does the record's triangle cover `column` just after now (local time s on its segment)?
  /// `own`, if given, is the edge function of the record's boundary `boundary` along `column`
  /// at s (the boundary event's), which is not evaluated again.
  [[nodiscard]] bool covers_now(uint32_t rec, int column, double s, uint32_t boundary = kNoBoundary,
                                const EdgeOnRay* own = nullptr) const;
  /// Brings one column of a record to `covered` (the interval moves by one column at an end).
  void set_pixel(uint32_t rec, int column, bool covered);
  /// The record's covered interval [lo, hi] once `column` joins (covered) or leaves it; false
  /// when the column is not at an end of it (several columns changed at one instant). Inline:
  /// every boundary event asks it twice.
  [[nodiscard]] static bool interval_after(const RowRecord& r, int column, bool covered, int& lo,
                                           int& hi) {
    lo = r.lo;
    hi = r.hi;
    if (covered) {
      if (r.empty())
        lo = hi = column;
      else if (column == r.lo - 1)
        lo = column;
      else if (column == r.hi + 1)
        hi = column;
      else
        return false;
    } else {
      if (r.lo == r.hi)
        lo = 0, hi = -1;
      else if (column == r.lo)
        ++lo;
      else if (column == r.hi)
        --hi;
      else
        return false;
    }
    return true;
  }
  /// Re-evaluates one column of a record.
  void update_pixel(uint32_t rec, int column, const TriangleNow& tn) {
    set_pixel(rec, column, covers_now(rec, column, tn.s));
  }

  // Boundaries.
  /// Ties boundary k of record rec (on its edge r.edge[k]) to the (edge, row) boundary, which is
  /// made (placed from `hint` if given and it agrees, else located) when no record holds it yet.
  /// Returns false if a hint was given and the boundary is not in the hint's slot.
  bool bind_boundary(uint32_t rec, int k, const SlotTracker* hint = nullptr);
  /// Unties boundary k of record rec; the boundary goes when no record holds it.
  void release_boundary(uint32_t rec, int k);
  /// Locates a boundary afresh (an event of it at this instant may still be pending); if that
  /// moves it, the records it bounds other than `rec` are rescanned.
  void relocate_boundary(uint32_t id, uint32_t rec);
  /// A boundary's signs changed at both watched columns at one instant (degenerate): it is
  /// located afresh and its records are rescanned.
  void rebuild_boundary(uint32_t id);
  void set_coverage(uint32_t rec, int lo, int hi);
  void update_triangle_row(uint32_t tri, int row);
  [[nodiscard]] uint32_t find_record(uint32_t tri, int row) const;
  void scan_triangle(uint32_t tri, const std::vector<RowPattern>& patterns);
  /// Creates the records of tri for the rows its vertices' patterns say it meets.
  void scan_rows(uint32_t tri, const std::array<RowPattern, 3>& p);
  /// True if tri, with these vertex patterns, meets some row of the band (never if two of its
  /// vertices are one: it covers nothing).
  [[nodiscard]] bool meets_rows(uint32_t tri, const std::array<RowPattern, 3>& p) const;
  /// The row patterns of a moving triangle's vertices, from their slot trackers.
  [[nodiscard]] std::array<RowPattern, 3> tracked_patterns(uint32_t tri) const;
  /// The row patterns of tri's vertices, from `patterns` (one per vertex of tri's mesh).
  [[nodiscard]] std::array<RowPattern, 3> mesh_patterns(uint32_t tri,
                                                        const std::vector<RowPattern>& patterns) const;
  /// Back-face culling: starts keeping the orientation of a triangle that comes to meet the
  /// band's rows, and creates its records (rows from `p`) if it faces the eye.
  void watch(uint32_t tri, const std::array<RowPattern, 3>& p);
  /// Back-face culling: the triangle no longer meets the band's rows; its records die and its
  /// orientation is no longer kept.
  void unwatch(uint32_t tri);
  /// Back-face culling (GridScene::cull_sign): the triangle meets no row of the band or faces
  /// away, so it has no records.
  [[nodiscard]] bool culled(uint32_t tri) const {
    const int cull = m_scene.cull_sign_of_triangle(tri);
    const TriangleState& ts = m_triangles[tri];
    return cull != 0 && (!ts.watched || ts.orientation != cull);
  }

  // Pixels.
  [[nodiscard]] size_t pixel_index(int column, int row) const {
    return size_t(row - m_row_begin) * size_t(m_width) + size_t(column);
  }
  /// Copies pixel k's front `tri` into m_fronts after a change of its order; true if the front
  /// changed.
  bool refresh_front(size_t k, uint32_t tri) {
    const bool changed = tri != m_fronts[k];
    m_fronts[k] = tri;
    if (changed && m_front_log) [[unlikely]]
      m_front_log->record(uint32_t(size_t(m_row_begin) * size_t(m_width) + k), m_sim.now(), tri);
    return changed;
  }
  void pixel_insert(uint32_t tri, int column, int row);
  /// Audit mode, after each change of a pixel order: the order's own audit; a problem is thrown
  /// as KineticAuditFailure with the band, the pixel and the time.
  void audit_pixel(int column, int row, double t) const;
  /// The brute-force audit, one member function per invariant (frustum_band_audit.cpp).
  class Audit;
  /// Tests corrupt a band's state through this to see the audit report it
  /// (tests/kinetic/grid/test_frustum_band.cpp); nothing else uses it.
  friend struct FrustumBandTestAccess;
  void pixel_erase(uint32_t tri, int column, int row);

  // Meshes.
  /// Attaches mesh m's triangles (scan conversion at now); counts them into `progress` if given.
  void insert_mesh(uint32_t m, WorkProgress* progress = nullptr);
  void remove_mesh(uint32_t m);

  // Events.
  void handle(const EventKey& key, uint64_t payload);
  void handle_flightplans(uint32_t first_mesh);
  void handle_boundary(uint32_t id);
  /// A boundary event of a point behind the eye: it may come back in front, into the off slot.
  void handle_boundary_behind_eye(uint32_t id, const EdgeNow& en, const EdgeNormal& edge);
  /// A boundary crossed `column`: the column passes between the records it bounds.
  void pass_column(uint32_t id, int column, double s, const EdgeOnRay& own);
  void handle_vertex(uint32_t v);
  void handle_orientation(uint32_t tri);
  void handle_swap(const EventKey& key, uint64_t payload);

  const GridScene& m_scene;
  Config m_config;
  int m_row_begin, m_row_end, m_width;
  SlotCircle m_columns, m_rows;
  Simulator m_sim;  ///< the band's clock and event queue
  BandMotion m_motion;  ///< the current segment of every mesh and its vertex motions
  std::vector<MeshState> m_meshes;
  std::vector<TriangleState> m_triangles;
  std::vector<SlotTracker> m_vertices;  ///< by global vertex id; used for moving meshes
  std::vector<RowRecord> m_records;
  std::vector<uint32_t> m_free_records;
  std::vector<EdgeBoundary> m_boundaries;
  std::vector<uint32_t> m_free_boundaries;
  std::vector<uint32_t> m_edge_heads;  ///< per global edge: its first boundary in the band
  KineticSortStats m_sort_stats;       ///< the pixel orders' counters, summed
  std::unique_ptr<PixelOrders> m_orders;  ///< one depth order per pixel, by pixel_index
  std::vector<uint32_t> m_fronts;   ///< per pixel: its order's front, or kNoFront
  std::vector<uint8_t> m_pixel_marks;     ///< per pixel: listed by the key being handled
  FrontChangeLog* m_front_log = nullptr;  ///< motion blur: where front changes go, if anywhere

  GridStats m_stats;
  bool m_front_changed = false;  ///< set by pixel changes during one event
  std::vector<uint32_t> m_watch_changed;  ///< handle_vertex: triangles (un)watched by this event
  uint64_t m_live_boundaries = 0, m_live_vertices = 0, m_live_orientations = 0;
};

}  // namespace kinray
