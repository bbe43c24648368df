#include "kinetic/grid/frustum_grid.h"

#include <emmintrin.h>
#include <oneapi/tbb/enumerable_thread_specific.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <limits>
#include <optional>
#include <stdexcept>

#include "kinetic/core/root_finding.h"
#include "kinetic/grid/frustum_band.h"
#include "kinetic/grid/plane_pairs.h"
#include "util/parallel.h"
#include "util/stopwatch.h"

namespace kinray {

namespace {

constexpr int kBandsPerThread = 4;
constexpr size_t kPlaneCache = 2048;  ///< read-out: planes kept per thread (a few rows' runs)
constexpr int kReadoutBlocksPerThread = 8;  ///< read-out: blocks of rows handed out per thread
constexpr size_t kReadoutMinBlockRows = 16;

/// Where each mesh is on its key grid at t: what a read-out at t interpolates with.
std::vector<FlightplanMesh::KeyBlend> key_blends(const GridScene& scene, double t) {
  std::vector<FlightplanMesh::KeyBlend> blends(scene.mesh_count());
  for (uint32_t m = 0; m < scene.mesh_count(); ++m) blends[m] = scene.mesh(m).blend_at(t);
  return blends;
}

/// A read-out's buffers hold the image's pixels each: else std::invalid_argument.
void check_buffers(const GridScene& scene, std::span<const uint32_t> object,
                   std::span<const uint32_t> prim, std::span<const float> depth) {
  const size_t n = size_t(scene.width()) * size_t(scene.height());
  if (object.size() != n || prim.size() != n || depth.size() != n)
    throw std::invalid_argument("kinetic grid read-out: buffers must have width x height pixels");
}

/// An audit after an advance: throws std::logic_error listing the first problems, if any.
void throw_audit_problems(const std::vector<std::string>& problems) {
  if (problems.empty()) return;
  std::string text = "kinetic grid audit failed (" + std::to_string(problems.size()) + "):";
  for (size_t k = 0; k < std::min<size_t>(problems.size(), 5); ++k) text += "\n  " + problems[k];
  throw std::logic_error(text);
}

}  // namespace

/// The bands of rows, each simulated on its own: the grid's work is handed out by band.
class FrustumGrid::Bands {
 public:
  Bands(const GridScene& scene, int bands, DepthSortKind sort, bool audit, WorkProgress* init_progress) {
    const int h = scene.height();
    for (int b = 0; b < bands; ++b) {
      const int r0 = int(int64_t(h) * b / bands), r1 = int(int64_t(h) * (b + 1) / bands);
      FrustumBand::Config config;
      config.sort = sort;
      config.audit = audit;
      config.counts_meshes = b == 0;
      config.init_progress = init_progress;
      m_bands.push_back(std::make_unique<FrustumBand>(scene, r0, r1, config));
      m_row_begin.push_back(r0);
    }
    m_row_begin.push_back(h);
  }
  void start(double t0, int threads) {
    parallel_for_dynamic(m_bands.size(), threads, [&](size_t b) { m_bands[b]->start(t0); });
  }
  void advance_to(double t, int threads) {
    parallel_for_dynamic(m_bands.size(), threads, [&](size_t b) { m_bands[b]->advance_to(t); });
  }
  /// The front triangles (global ids, kNoGridHit for none) of the width pixels of row j.
  [[nodiscard]] const uint32_t* front_row(int j) const {
    static_assert(kNoFront == kNoGridHit);
    return m_bands[band_of(j)]->front_row(j);
  }
  [[nodiscard]] uint32_t front(int i, int j) const {
    return m_bands[band_of(j)]->front(i, j).value_or(kNoGridHit);
  }
  /// Every triangle of pixel (i, j)'s order into `out` (cleared first): front to back for the
  /// sorted list, the front first for the tournament and the heap.
  void members(int i, int j, std::vector<uint32_t>& out) const { m_bands[band_of(j)]->members(i, j, out); }
  [[nodiscard]] size_t depth_complexity(int i, int j) const {
    return m_bands[band_of(j)]->depth_complexity(i, j);
  }
  [[nodiscard]] std::vector<std::string> audit(double t, int threads) const {
    std::vector<std::vector<std::string>> found(m_bands.size());
    parallel_for_dynamic(m_bands.size(), threads, [&](size_t b) { found[b] = m_bands[b]->audit(t); });
    std::vector<std::string> all;
    for (auto& f : found) all.insert(all.end(), f.begin(), f.end());
    return all;
  }
  [[nodiscard]] GridStats stats() const {
    GridStats s;
    for (const auto& band : m_bands) s += band->stats();
    return s;
  }
  [[nodiscard]] int count() const { return int(m_bands.size()); }
  [[nodiscard]] FrustumBand& band(size_t b) { return *m_bands[b]; }
  /// The rows [first, second) of band b.
  [[nodiscard]] std::pair<int, int> rows(size_t b) const {
    return {m_row_begin[b], m_row_begin[b + 1]};
  }
  /// Band b logs its front changes into logs[b] (logs == nullptr: no band logs).
  void set_front_logs(FrontChangeLog* logs) {
    for (size_t b = 0; b < m_bands.size(); ++b) m_bands[b]->set_front_log(logs ? &logs[b] : nullptr);
  }

 private:
  [[nodiscard]] size_t band_of(int row) const {
    return size_t(std::upper_bound(m_row_begin.begin(), m_row_begin.end(), row) - m_row_begin.begin()) - 1;
  }
  std::vector<std::unique_ptr<FrustumBand>> m_bands;
  std::vector<int> m_row_begin;
};

FrustumGrid::FrustumGrid(GridInput input, double start_time, const FrustumGridConfig& config)
    : m_created(std::chrono::steady_clock::now()), m_scene(std::move(input), config.threads, config.init_progress), m_config(config),
      m_now(start_time) {
  m_threads = resolve_threads(config.threads);
  // The events gather where the geometry moves (a horizon, a fold of the cloth), so with several
  // threads the rows are split into more bands than threads, handed out dynamically: a band
  // costs a little (its vertex and orientation certificates at each key), an idle thread much
  // more. One thread gets several bands too: a band's events, run to the frame time before the
  // next band's, touch its rows' pixels, records and queue only, which stay in cache, where one
  // band's stream of events hops over the whole image (one thread, wavy-sphere at 40,000
  // triangles, 512x512: 918 -> 580 ns per event with 8 bands, 640 with 4, 750 with 16, whose
  // keys cost more than the cache saves; docs/kinetic_grid.md, "Bands on one core").
  const int automatic = kBandsPerThread * m_threads;
  const int bands = std::clamp(config.bands > 0 ? config.bands : automatic, 1, m_scene.height());
  m_bands = std::make_unique<Bands>(m_scene, bands, config.sort, config.audit, config.init_progress);
  if (config.init_progress != nullptr) {
    uint64_t present = 0;
    for (uint32_t m = 0; m < m_scene.mesh_count(); ++m)
      if (m_scene.mesh(m).present(start_time))
        present += m_scene.triangle_end(m) - m_scene.triangle_begin(m);
    config.init_progress->begin("scan conversion", present * uint64_t(bands));
  }
  m_bands->start(start_time, m_threads);
  m_timings.init = seconds_since(m_created);
  m_memory_peak = m_bands->stats().memory_bytes;
  if (config.audit) {
    const auto problems = audit();
    if (!problems.empty()) throw std::logic_error("kinetic grid audit at start: " + problems.front());
  }
}

FrustumGrid::~FrustumGrid() = default;

int FrustumGrid::band_count() const { return m_bands->count(); }

void FrustumGrid::log_front_changes(bool on) {
  m_front_logs.resize(on ? size_t(m_bands->count()) : 0);
  m_bands->set_front_logs(on ? m_front_logs.data() : nullptr);
}

void FrustumGrid::advance_to(double t) {
  if (!(t >= m_now)) throw std::invalid_argument("kinetic grid: frame times must not decrease");
  const auto started = std::chrono::steady_clock::now();
  m_bands->advance_to(t, m_threads);
  m_now = t;
  m_timings.events += seconds_since(started);
  m_memory_peak = std::max(m_memory_peak, m_bands->stats().memory_bytes);
  if (m_config.audit) throw_audit_problems(audit());
}

std::optional<GridHit> FrustumGrid::front(int i, int j) const {
  const uint32_t tri = m_bands->front(i, j);
  if (tri == kNoGridHit) return std::nullopt;
  const uint32_t m = m_scene.mesh_of_triangle(tri);
  return GridHit{m, tri - m_scene.triangle_begin(m)};
}

size_t FrustumGrid::depth_complexity(int i, int j) const { return m_bands->depth_complexity(i, j); }

namespace {

/// One read-out thread: the rows it is handed, written into the buffers. Everything the per-pixel
/// loop reads is a member or a local (not reached through references the buffers' stores could
/// alias), and the rare paths are out of line, so the loop keeps its state in registers.
class RowReader {
 public:
  RowReader(const GridScene& scene, const FrustumGrid::Bands& bands,
            std::span<const FlightplanMesh::KeyBlend> blends)
      : m_scene(scene), m_bands(bands), m_blends(blends), m_width(scene.width()),
        m_column_x(size_t(scene.width())), m_cache(kPlaneCache), m_missing(size_t(scene.width())) {
    for (int i = 0; i < m_width; ++i) m_column_x[size_t(i)] = scene.column_x(i);
  }

  /// Reads out at another time: each mesh's place on its key grid then; the cached planes were
  /// another time's.
  void set_blends(std::span<const FlightplanMesh::KeyBlend> blends) {
    m_blends = blends;
    for (CachedPlane& c : m_cache) c.tri = kNoGridHit;
  }

  /// Row j of the read-out into the rows of the buffers, written with non-temporal stores
  /// through a row that stays in cache: for frames read out ahead, which nobody reads before the
  /// batch is done. Plain stores would first fetch every line of the buffers only to overwrite
  /// it, and evict the band's own data on the way (docs/kinetic_grid.md, "Frames in batches").
  void read_streaming(int j, uint32_t* object, uint32_t* prim, float* depth) {
    const size_t w = size_t(m_width);
    m_row_object.resize(w);
    m_row_prim.resize(w);
    m_row_depth.resize(w);
    read(j, m_row_object.data(), m_row_prim.data(), m_row_depth.data());
    stream_copy(object, m_row_object.data(), w);
    stream_copy(prim, m_row_prim.data(), w);
    stream_copy(depth, m_row_depth.data(), w);
  }

  /// Row j of the read-out into the rows of the buffers.
  void read(int j, uint32_t* object, uint32_t* prim, float* depth) {
    const uint32_t* fronts = m_bands.front_row(j);
    const int width = m_width;
    // Background comes in long runs (a few per row), filled in bulk; the covered runs between
    // them are noted, with the triangles whose planes are not in the cache. Those planes are
    // computed before any depth, two at a time: a miss met pixel by pixel would be a mispredicted
    // branch each time.
    m_segments.clear();
    size_t missing = 0;
    int i = 0;
    while (i < width) {
      int end = i;
      for (; end + 4 <= width; end += 4) {  // four pixels at once: kNoGridHit has every bit set
        uint64_t a = 0, b = 0;
        std::memcpy(&a, fronts + end, sizeof a);
        std::memcpy(&b, fronts + end + 2, sizeof b);
        if ((a & b) != ~uint64_t(0)) break;
      }
      while (end < width && fronts[end] == kNoGridHit) ++end;
      std::fill(object + i, object + end, kNoGridHit);
      std::fill(prim + i, prim + end, kNoGridHit);
      std::fill(depth + i, depth + end, std::numeric_limits<float>::infinity());
      if (end == width) break;
      uint32_t previous = kNoGridHit;
      for (i = end; i < width && fronts[i] != kNoGridHit; ++i) {
        const uint32_t tri = fronts[i];
        m_missing[missing] = tri;  // kept when it starts a run and is not cached: no branch
        missing += size_t(tri != previous) & size_t(m_cache[tri % kPlaneCache].tri != tri);
        previous = tri;
      }
      m_segments.emplace_back(end, i);
    }
    size_t k = 0;
    for (; k + 2 <= missing; k += 2) fill_pair(m_missing[k], m_missing[k + 1]);
    if (k < missing) plane(m_missing[k]);
    const double y = m_scene.row_y(j);
    const double* xs = m_column_x.data();
    for (const auto& [begin, end] : m_segments) {
      // Two pixels at a time (one division for both, plane_pairs.h). A triangle covers only
      // a couple of pixels of a row, so its changes are not branched on: every pixel looks its
      // triangle's plane up in the cache.
      int p = begin;
      for (; p + 2 <= end; p += 2) {
        const uint32_t t0 = fronts[p], t1 = fronts[p + 1];
        const CachedPlane& c0 = plane(t0);
        const CachedPlane& c1 = plane(t1);
        DoublePair x;
        std::memcpy(&x, xs + p, sizeof x);
        const DoublePair z = plane_depth_pair(c0.plane, c1.plane, x, y);
        // c0 was evicted by c1 (two triangles of one cache slot), or a front does not pierce.
        if (c0.tri != t0 || !pierces(z[0]) || !pierces(z[1])) [[unlikely]] {
          pixel(p, j, t0, y, object, prim, depth);
          pixel(p + 1, j, t1, y, object, prim, depth);
          continue;
        }
        object[p] = c0.mesh_id;
        object[p + 1] = c1.mesh_id;
        prim[p] = c0.local;
        prim[p + 1] = c1.local;
        depth[p] = float(z[0]);
        depth[p + 1] = float(z[1]);
      }
      if (p < end) pixel(p, j, fronts[p], y, object, prim, depth);
    }
  }

 private:
  /// A triangle meets a few consecutive rows: the planes of recent rows are kept in a small
  /// direct-mapped cache (plane_of's values bit for bit, also from fill_pair, so the same depths).
  struct CachedPlane {
    uint32_t tri = kNoGridHit, mesh_id = 0, local = 0;
    TrianglePlane plane{Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()};
  };

  /// A triangle in a pixel's order pierces its ray just after now; exactly at now it may not: when
  /// its plane holds the eye (det = 0, e.g. a vertex passing through the eye) it covers nothing at
  /// that instant (the strict sign rule, docs/design.md), and its hit is not in front of the eye.
  /// That is measure zero, so the front is checked and only then are the other members visited.
  static bool pierces(double z) { return std::isfinite(z) && z > 0; }

  /// The plane of triangle `tri` at now, from its interpolated vertices.
  [[nodiscard]] TrianglePlane plane_of(uint32_t tri) const {
    const uint32_t m = m_scene.mesh_of_triangle(tri);
    const FlightplanMesh& mesh = m_scene.mesh(m);
    const auto& vs = mesh.triangles[tri - m_scene.triangle_begin(m)];
    return TrianglePlane(mesh.position(vs[0], m_blends[m]), mesh.position(vs[1], m_blends[m]),
                         mesh.position(vs[2], m_blends[m]));
  }

  /// Triangle tri's slot of the cache, filled if it held another triangle.
  const CachedPlane& plane(uint32_t tri) {
    CachedPlane& c = m_cache[tri % kPlaneCache];
    if (c.tri != tri) [[unlikely]]
      fill(c, tri);
    return c;
  }

  /// Pixel (i, j), whose front is tri, one at a time.
  void pixel(int i, int j, uint32_t tri, double y, uint32_t* object, uint32_t* prim, float* depth) {
    const CachedPlane& c = plane(tri);
    const double z = c.plane.depth(m_column_x[size_t(i)], y);
    if (!pierces(z)) [[unlikely]] {
      nearest_piercing(i, j, tri, object[i], prim[i], depth[i]);
      return;
    }
    object[i] = c.mesh_id;
    prim[i] = c.local;
    depth[i] = float(z);
  }

  [[gnu::noinline]] void fill(CachedPlane& c, uint32_t tri) const {
    const uint32_t m = m_scene.mesh_of_triangle(tri);
    c.tri = tri;
    c.mesh_id = m_scene.mesh(m).id;
    c.local = tri - m_scene.triangle_begin(m);
    c.plane = plane_of(tri);
  }

  /// The planes of two triangles into their slots, computed together (plane_pairs.h); when both
  /// have one slot the second stays, and the pixel loop refills the first.
  void fill_pair(uint32_t t0, uint32_t t1) {
    const uint32_t m0 = m_scene.mesh_of_triangle(t0), m1 = m_scene.mesh_of_triangle(t1);
    const FlightplanMesh::KeyBlend &b0 = m_blends[m0], &b1 = m_blends[m1];
    if (b0.still || b1.still) {  // the positions are the keys', unblended
      fill(m_cache[t0 % kPlaneCache], t0);
      fill(m_cache[t1 % kPlaneCache], t1);
      return;
    }
    const FlightplanMesh &mesh0 = m_scene.mesh(m0), &mesh1 = m_scene.mesh(m1);
    const uint32_t local0 = t0 - m_scene.triangle_begin(m0), local1 = t1 - m_scene.triangle_begin(m1);
    const auto &vs0 = mesh0.triangles[local0], &vs1 = mesh1.triangles[local1];
    const DoublePair alpha = {b0.alpha, b1.alpha};
    auto vertex = [&](int v) {
      return blend_pair(point_pair(mesh0.key_position(b0.k, vs0[v]), mesh1.key_position(b1.k, vs1[v])),
                        point_pair(mesh0.key_position(b0.k + 1, vs0[v]), mesh1.key_position(b1.k + 1, vs1[v])),
                        alpha);
    };
    CachedPlane& c0 = m_cache[t0 % kPlaneCache];
    CachedPlane& c1 = m_cache[t1 % kPlaneCache];
    TrianglePlane plane1 = c1.plane;
    triangle_plane_pair(vertex(0), vertex(1), vertex(2), c0.plane, plane1);
    c0.tri = t0;
    c0.mesh_id = mesh0.id;
    c0.local = local0;
    c1.tri = t1;
    c1.mesh_id = mesh1.id;
    c1.local = local1;
    c1.plane = plane1;
  }

  /// Pixel (i, j) whose front does not pierce its ray at now: the nearest member that does, at
  /// equal depths the earlier one in the order (the sorted list visits front to back).
  [[gnu::noinline]] void nearest_piercing(int i, int j, uint32_t front, uint32_t& object,
                                          uint32_t& prim, float& depth) {
    const double x = m_scene.column_x(i), y = m_scene.row_y(j);
    uint32_t tri = kNoGridHit;
    double z = 0;
    m_bands.members(i, j, m_members);
    for (uint32_t other : m_members) {
      if (other == front) continue;
      const double zo = plane_of(other).depth(x, y);
      if (pierces(zo) && (tri == kNoGridHit || zo < z)) {
        tri = other;
        z = zo;
      }
    }
    if (tri == kNoGridHit) {
      object = prim = kNoGridHit;
      depth = std::numeric_limits<float>::infinity();
      return;
    }
    const uint32_t m = m_scene.mesh_of_triangle(tri);
    object = m_scene.mesh(m).id;
    prim = tri - m_scene.triangle_begin(m);
    depth = float(z);
  }

  /// n four-byte values from src to dst, with non-temporal stores where dst is 16-byte aligned
  /// (the caller fences before the buffers are handed over).
  template <class T>
  static void stream_copy(T* dst, const T* src, size_t n) {
    static_assert(sizeof(T) == 4);
    size_t k = 0;
    for (; k < n && (reinterpret_cast<uintptr_t>(dst + k) & 15) != 0; ++k) dst[k] = src[k];
    for (; k + 4 <= n; k += 4)
      _mm_stream_si128(reinterpret_cast<__m128i*>(dst + k),
                       _mm_loadu_si128(reinterpret_cast<const __m128i*>(src + k)));
    for (; k < n; ++k) dst[k] = src[k];
  }

  std::vector<uint32_t> m_row_object, m_row_prim;  ///< read_streaming's row
  std::vector<float> m_row_depth;

  const GridScene& m_scene;
  const FrustumGrid::Bands& m_bands;
  std::span<const FlightplanMesh::KeyBlend> m_blends;  ///< each mesh's place on its key grid at now
  int m_width;
  std::vector<double> m_column_x;
  std::vector<CachedPlane> m_cache;
  std::vector<uint32_t> m_members;
  std::vector<std::pair<int, int>> m_segments;  ///< a row's covered runs [begin, end)
  std::vector<uint32_t> m_missing;  ///< a row's triangles whose planes were not cached
};

}  // namespace

void FrustumGrid::read_out(std::span<uint32_t> object, std::span<uint32_t> prim,
                           std::span<float> depth) const {
  const auto started = std::chrono::steady_clock::now();
  check_buffers(m_scene, object, prim, depth);
  const int w = m_scene.width(), h = m_scene.height();
  // Where each mesh is on its key grid at now, once per frame.
  const std::vector<FlightplanMesh::KeyBlend> blends = key_blends(m_scene, m_now);
  // Rows are handed out in blocks: a thread that starts late (the machine is shared) takes fewer,
  // and a block is long enough that the plane cache is reused from row to row.
  const size_t block_rows =
      std::max<size_t>(kReadoutMinBlockRows, size_t(h) / size_t(kReadoutBlocksPerThread * m_threads));
  const size_t blocks = (size_t(h) + block_rows - 1) / block_rows;
  // One reader (its plane cache, its row buffers) per thread, made when the thread takes its first
  // block.
  tbb::enumerable_thread_specific<RowReader> readers(
      [&] { return RowReader(m_scene, *m_bands, blends); });
  parallel_for_dynamic(blocks, m_threads, [&](size_t b) {
    RowReader& reader = readers.local();
    for (size_t j = b * block_rows; j < std::min(size_t(h), (b + 1) * block_rows); ++j) {
      const size_t row = j * size_t(w);
      reader.read(int(j), object.data() + row, prim.data() + row, depth.data() + row);
    }
  });
  m_timings.readout += seconds_since(started);
}

void FrustumGrid::advance_and_read_out(std::span<BatchFrame> frames) {
  if (frames.empty()) return;
  const int w = m_scene.width();
  double previous = m_now;
  for (const BatchFrame& f : frames) {
    if (!(f.t >= previous))
      throw std::invalid_argument("kinetic grid: frame times must not decrease");
    check_buffers(m_scene, f.object, f.prim, f.depth);
    previous = f.t;
  }
  const auto started = std::chrono::steady_clock::now();
  const size_t count = frames.size(), bands = size_t(m_bands->count());
  std::vector<std::vector<FlightplanMesh::KeyBlend>> blends(count);
  for (size_t f = 0; f < count; ++f) blends[f] = key_blends(m_scene, frames[f].t);
  // Per band and frame: seconds of events and of read-out on the thread that ran it, and events.
  std::vector<double> events_s(bands * count), readout_s(bands * count);
  std::vector<uint64_t> events(bands * count);
  tbb::enumerable_thread_specific<RowReader> readers(
      [&] { return RowReader(m_scene, *m_bands, blends.front()); });
  parallel_for_dynamic(bands, m_threads, [&](size_t b) {
    RowReader& reader = readers.local();
    FrustumBand& band = m_bands->band(b);
    const auto [first_row, end_row] = m_bands->rows(b);
    for (size_t f = 0; f < count; ++f) {
      const BatchFrame& frame = frames[f];
      const auto start = std::chrono::steady_clock::now();
      const uint64_t before = band.event_total();
      band.advance_to(frame.t);
      if (m_config.audit) throw_audit_problems(band.audit(frame.t));
      events[b * count + f] = band.event_total() - before;
      const auto advanced = std::chrono::steady_clock::now();
      reader.set_blends(blends[f]);
      for (int j = first_row; j < end_row; ++j) {
        const size_t row = size_t(j) * size_t(w);
        reader.read_streaming(j, frame.object.data() + row, frame.prim.data() + row,
                              frame.depth.data() + row);
      }
      events_s[b * count + f] = std::chrono::duration<double>(advanced - start).count();
      readout_s[b * count + f] = seconds_since(advanced);
    }
    _mm_sfence();  // the streamed rows are written before the batch is handed over
  });
  // The threads' seconds are shared out over the batch's wall-clock time, so that the frames'
  // timings add up to it as advance_to's and read_out's do.
  double busy = 0;
  for (size_t k = 0; k < bands * count; ++k) busy += events_s[k] + readout_s[k];
  const double wall = seconds_since(started), scale = busy > 0 ? wall / busy : 0;
  for (size_t f = 0; f < count; ++f) {
    BatchFrame& frame = frames[f];
    frame.events_s = frame.readout_s = 0;
    frame.events = 0;
    for (size_t b = 0; b < bands; ++b) {
      frame.events_s += scale * events_s[b * count + f];
      frame.readout_s += scale * readout_s[b * count + f];
      frame.events += events[b * count + f];
    }
    m_timings.events += frame.events_s;
    m_timings.readout += frame.readout_s;
  }
  m_now = frames.back().t;
  m_memory_peak = std::max(m_memory_peak, m_bands->stats().memory_bytes);
}

std::vector<std::string> FrustumGrid::audit() const { return m_bands->audit(m_now, m_threads); }

GridStats FrustumGrid::stats() const {
  GridStats s = m_bands->stats();
  uint64_t present = 0, culled = 0;
  for (uint32_t m = 0; m < m_scene.mesh_count(); ++m) {
    if (!m_scene.mesh(m).present(m_now)) continue;
    present += m_scene.triangle_end(m) - m_scene.triangle_begin(m);
    const int cull = m_scene.cull_sign(m);
    if (cull == 0) continue;
    const MeshSegment seg = m_scene.segment_at(m, m_now);
    for (uint32_t tri = m_scene.triangle_begin(m); tri < m_scene.triangle_end(m); ++tri)
      if (sign_after(m_scene.triangle_motion(tri, seg).orientation(), m_now - seg.origin) != cull)
        ++culled;
  }
  s.triangles_present = present;
  s.triangles_culled = culled;
  return s;
}

uint64_t FrustumGrid::event_count() const { return m_bands->stats().events.total(); }

}  // namespace kinray
