#pragma once
// The kinetic grid of frusta (docs/design.md): for every pixel the triangles its centre ray
// pierces, in depth order, kept up to date by events only. Coverage is tracked per (triangle, row)
// by boundary, vertex-row and orientation certificates, depth per pixel by a kinetic sorted list,
// tournament or heap with degree-5 certificates; flightplan updates at keyframes, meshes that
// appear and disappear, and static meshes (no coverage events) are handled. Rows are split into
// bands simulated in parallel on their own event queues; the frames do not depend on the split.
//
//   FrustumGrid grid(input, t0, {.sort = DepthSortKind::kTournament});
//   for (double t : frame_times) { grid.advance_to(t); grid.read_out(t, object, prim, depth); }
//
// Nothing is rasterized or traced per frame: a read-out costs one look-up per pixel.
// See docs/kinetic_grid.md.
#include <chrono>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "kinetic/grid/front_change_log.h"
#include "kinetic/grid/grid_input.h"
#include "kinetic/grid/grid_scene.h"
#include "kinetic/grid/grid_stats.h"
#include "kinetic/sort/depth_sort_kind.h"
#include "util/work_progress.h"

namespace kinray {

struct FrustumGridConfig {
  int threads = 0;  ///< worker threads; 0: all cores
  int bands = 0;    ///< bands of rows; 0: four per thread
  DepthSortKind sort = DepthSortKind::kList;
  /// Audit every invariant after each advance (and every touched pixel order after each
  /// change); a violation throws std::logic_error.
  bool audit = false;
  /// When given, the constructor counts its two long steps here (the back-face culling proof,
  /// then the scan conversion), so a caller can show how far a long initialisation has got; it
  /// must outlive the constructor.
  WorkProgress* init_progress = nullptr;
};

/// A pixel's front triangle.
struct GridHit {
  uint32_t mesh = 0;      ///< index into GridInput::meshes
  uint32_t triangle = 0;  ///< index into that mesh's triangles
};

inline constexpr uint32_t kNoGridHit = ~0u;

/// One frame of FrustumGrid::advance_and_read_out: its time and read-out buffers (width * height
/// each, as read_out's), and what the grid spent on it.
struct BatchFrame {
  double t = 0;
  std::span<uint32_t> object, prim;
  std::span<float> depth;
  double events_s = 0;   ///< out: wall-clock seconds of its events (the batch's, shared out)
  double readout_s = 0;  ///< out: wall-clock seconds of its read-out
  uint64_t events = 0;   ///< out: events processed on the way to it from the frame before
};

/// Wall-clock seconds spent by the grid.
struct GridTimings {
  double init = 0;     ///< indexing and scan conversion at the start time
  double events = 0;   ///< advance_to
  double readout = 0;  ///< read_out
};

class FrustumGrid {
 public:
  /// Builds the grid at start_time by scan conversion. The meshes' spans must outlive the grid.
  FrustumGrid(GridInput input, double start_time, const FrustumGridConfig& config = {});
  ~FrustumGrid();
  FrustumGrid(const FrustumGrid&) = delete;
  FrustumGrid& operator=(const FrustumGrid&) = delete;

  /// Processes every event with time <= t (t must not decrease).
  void advance_to(double t);
  [[nodiscard]] double now() const { return m_now; }

  [[nodiscard]] std::optional<GridHit> front(int i, int j) const;
  /// Number of triangles whose centre-ray hits pixel (i, j) holds.
  [[nodiscard]] size_t depth_complexity(int i, int j) const;
  /// Read-out at now(), row-major with row 0 at the top: the front triangle's FlightplanMesh::id
  /// and triangle index (kNoGridHit for background) and its exact depth along the centre ray at now
  /// (when the front does not pierce the ray exactly at now -- its plane holds the eye -- the
  /// nearest member of the pixel's order that does),
  /// computed in double from the interpolated positions exactly as the Embree backend does (+inf
  /// for background). Spans of width * height.
  void read_out(std::span<uint32_t> object, std::span<uint32_t> prim, std::span<float> depth) const;

  /// advance_to(f.t) then read_out(f's buffers) for each frame f in turn (times non-decreasing),
  /// with the same buffers, events and audits, but band by band: each band runs to every frame
  /// of the batch and reads its rows out at each before the next band starts. A band's events
  /// touch its own rows' pixels, records and queue only, so a batch keeps them in cache for all
  /// its frames, where frame by frame every band's data is evicted by the others' before it is
  /// met again (docs/kinetic_grid.md, "Frames in batches"). now() is the last frame's time after.
  void advance_and_read_out(std::span<BatchFrame> frames);

  /// Every invariant checked by brute force at now(); the problems found (empty: none).
  [[nodiscard]] std::vector<std::string> audit() const;
  /// Every counter; triangles_culled is found from the geometry at now() (bands keep the
  /// orientation only of the triangles that meet their rows), one pass over the culled meshes.
  [[nodiscard]] GridStats stats() const;
  /// stats().events.total() without that pass, for callers that count events every frame.
  [[nodiscard]] uint64_t event_count() const;
  [[nodiscard]] const GridTimings& timings() const { return m_timings; }
  /// Largest memory_bytes seen after initialisation and after each advance.
  [[nodiscard]] size_t memory_bytes_peak() const { return m_memory_peak; }
  [[nodiscard]] int band_count() const;
  /// Motion blur: while on, every front change made by advance_to is appended, with its event
  /// time, to the log of the band that made it (kinetic/grid/front_change_log.h); the caller reads
  /// and clears the logs. Off (the default) costs one null test per front change.
  void log_front_changes(bool on);
  /// One log per band, each in time order (empty when logging is off).
  [[nodiscard]] std::span<FrontChangeLog> front_logs() { return m_front_logs; }
  [[nodiscard]] const GridScene& scene() const { return m_scene; }
  [[nodiscard]] const FrustumGridConfig& config() const { return m_config; }

  class Bands;  ///< the bands of rows (frustum_grid.cpp)

 private:
  std::chrono::steady_clock::time_point m_created;  ///< initialisation timing starts here
  GridScene m_scene;
  FrustumGridConfig m_config;
  int m_threads = 1;
  double m_now = 0;
  std::unique_ptr<Bands> m_bands;
  std::vector<FrontChangeLog> m_front_logs;  ///< motion blur: one per band while logging
  mutable GridTimings m_timings;
  size_t m_memory_peak = 0;
};

}  // namespace kinray
