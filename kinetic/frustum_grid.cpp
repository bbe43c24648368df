#include "kinetic/frustum_grid.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>

#include "kinetic/frustum_band.h"
#include "kinetic/kinetic_heap.h"
#include "kinetic/kinetic_sorted_list.h"
#include "kinetic/kinetic_tournament.h"
#include "kinetic/parallel.h"
#include "kinetic/root_finding.h"

namespace kinray {

namespace {

constexpr int kBandsPerThread = 4;
constexpr size_t kPlaneCache = 1024;  ///< read-out: planes kept per thread (a few rows' runs)
constexpr int kReadoutBlocksPerThread = 8;  ///< read-out: blocks of rows handed out per thread
constexpr size_t kReadoutMinBlockRows = 16;

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

DepthSortKind parse_depth_sort(const std::string& name) {
  if (name == "list") return DepthSortKind::kList;
  if (name == "tournament") return DepthSortKind::kTournament;
  if (name == "heap") return DepthSortKind::kHeap;
  throw std::invalid_argument("unknown depth sort '" + name + "' (list, tournament or heap)");
}

const char* depth_sort_name(DepthSortKind kind) {
  switch (kind) {
    case DepthSortKind::kList: return "list";
    case DepthSortKind::kTournament: return "tournament";
    case DepthSortKind::kHeap: return "heap";
  }
  return "?";
}

// The virtual calls are per advance or per read-out, never per event.
class FrustumGrid::Bands {
 public:
  virtual ~Bands() = default;
  virtual void start(double t0, int threads) = 0;
  virtual void advance_to(double t, int threads) = 0;
  /// The front triangles (global ids, kNoGridHit for none) of the width pixels of row j.
  virtual const uint32_t* front_row(int j) const = 0;
  virtual size_t depth_complexity(int i, int j) const = 0;
  virtual uint32_t front(int i, int j) const = 0;
  /// Every triangle of pixel (i, j)'s order into `out` (cleared first): front to back for the
  /// sorted list, the front first for the tournament and the heap.
  virtual void members(int i, int j, std::vector<uint32_t>& out) const = 0;
  virtual std::vector<std::string> audit(double t, int threads) const = 0;
  virtual GridStats stats() const = 0;
  virtual int count() const = 0;
};

namespace {

template <class Sort>
class BandsOf final : public FrustumGrid::Bands {
 public:
  BandsOf(const GridScene& scene, int bands, bool audit) {
    const int h = scene.height();
    for (int b = 0; b < bands; ++b) {
      const int r0 = int(int64_t(h) * b / bands), r1 = int(int64_t(h) * (b + 1) / bands);
      typename FrustumBand<Sort>::Config config;
      config.audit = audit;
      config.counts_meshes = b == 0;
      m_bands.push_back(std::make_unique<FrustumBand<Sort>>(scene, r0, r1, config));
      m_row_begin.push_back(r0);
    }
    m_row_begin.push_back(h);
  }
  void start(double t0, int threads) override {
    parallel_for_dynamic(m_bands.size(), threads, [&](size_t b) { m_bands[b]->start(t0); });
  }
  void advance_to(double t, int threads) override {
    parallel_for_dynamic(m_bands.size(), threads, [&](size_t b) { m_bands[b]->advance_to(t); });
  }
  const uint32_t* front_row(int j) const override {
    static_assert(kNoFront == kNoGridHit);
    return m_bands[band_of(j)]->front_row(j);
  }
  uint32_t front(int i, int j) const override {
    return m_bands[band_of(j)]->front(i, j).value_or(kNoGridHit);
  }
  void members(int i, int j, std::vector<uint32_t>& out) const override {
    out.clear();
    m_bands[band_of(j)]->for_each_member(i, j, [&](uint32_t tri) { out.push_back(tri); });
  }
  size_t depth_complexity(int i, int j) const override {
    return m_bands[band_of(j)]->depth_complexity(i, j);
  }
  std::vector<std::string> audit(double t, int threads) const override {
    std::vector<std::vector<std::string>> found(m_bands.size());
    parallel_for_dynamic(m_bands.size(), threads, [&](size_t b) { found[b] = m_bands[b]->audit(t); });
    std::vector<std::string> all;
    for (auto& f : found) all.insert(all.end(), f.begin(), f.end());
    return all;
  }
  GridStats stats() const override {
    GridStats s;
    for (const auto& band : m_bands) s += band->stats();
    return s;
  }
  int count() const override { return int(m_bands.size()); }

 private:
  size_t band_of(int row) const {
    return size_t(std::upper_bound(m_row_begin.begin(), m_row_begin.end(), row) - m_row_begin.begin()) - 1;
  }
  std::vector<std::unique_ptr<FrustumBand<Sort>>> m_bands;
  std::vector<int> m_row_begin;
};

}  // namespace

FrustumGrid::FrustumGrid(GridInput input, double start_time, const FrustumGridConfig& config)
    : m_created(std::chrono::steady_clock::now()), m_scene(std::move(input), config.threads), m_config(config),
      m_now(start_time) {
  m_threads = resolve_threads(config.threads);
  // The events gather where the geometry moves (a horizon, a fold of the cloth), so with several
  // threads the rows are split into more bands than threads, handed out dynamically: a band
  // costs a little (its vertex and orientation certificates), an idle thread much more.
  const int automatic = m_threads == 1 ? 1 : kBandsPerThread * m_threads;
  const int bands = std::clamp(config.bands > 0 ? config.bands : automatic, 1, m_scene.height());
  switch (config.sort) {
    case DepthSortKind::kList:
      m_bands = std::make_unique<BandsOf<KineticSortedList<PixelDepthKeys>>>(m_scene, bands, config.audit);
      break;
    case DepthSortKind::kTournament:
      m_bands = std::make_unique<BandsOf<KineticTournament<PixelDepthKeys>>>(m_scene, bands, config.audit);
      break;
    case DepthSortKind::kHeap:
      m_bands = std::make_unique<BandsOf<KineticHeap<PixelDepthKeys>>>(m_scene, bands, config.audit);
      break;
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

void FrustumGrid::advance_to(double t) {
  if (!(t >= m_now)) throw std::invalid_argument("kinetic grid: frame times must not decrease");
  const auto started = std::chrono::steady_clock::now();
  m_bands->advance_to(t, m_threads);
  m_now = t;
  m_timings.events += seconds_since(started);
  m_memory_peak = std::max(m_memory_peak, m_bands->stats().memory_bytes);
  if (m_config.audit) {
    const auto problems = audit();
    if (!problems.empty()) {
      std::string text = "kinetic grid audit failed (" + std::to_string(problems.size()) + "):";
      for (size_t k = 0; k < std::min<size_t>(problems.size(), 5); ++k) text += "\n  " + problems[k];
      throw std::logic_error(text);
    }
  }
}

std::optional<GridHit> FrustumGrid::front(int i, int j) const {
  const uint32_t tri = m_bands->front(i, j);
  if (tri == kNoGridHit) return std::nullopt;
  const uint32_t m = m_scene.mesh_of_triangle(tri);
  return GridHit{m, tri - m_scene.triangle_begin(m)};
}

size_t FrustumGrid::depth_complexity(int i, int j) const { return m_bands->depth_complexity(i, j); }

void FrustumGrid::read_out(std::span<uint32_t> object, std::span<uint32_t> prim,
                           std::span<float> depth) const {
  const auto started = std::chrono::steady_clock::now();
  const int w = m_scene.width(), h = m_scene.height();
  const size_t n = size_t(w) * size_t(h);
  if (object.size() != n || prim.size() != n || depth.size() != n)
    throw std::invalid_argument("kinetic grid read-out: buffers must have width x height pixels");
  // Where each mesh is on its key grid at now, once per frame.
  std::vector<GridMesh::KeyBlend> blends(m_scene.mesh_count());
  for (uint32_t m = 0; m < m_scene.mesh_count(); ++m) blends[m] = m_scene.mesh(m).blend_at(m_now);
  // The plane of triangle `tri` at now, from its interpolated vertices.
  auto plane_of = [&](uint32_t tri) {
    const uint32_t m = m_scene.mesh_of_triangle(tri);
    const GridMesh& mesh = m_scene.mesh(m);
    const auto& vs = mesh.triangles[tri - m_scene.triangle_begin(m)];
    return TrianglePlane(mesh.position(vs[0], blends[m]), mesh.position(vs[1], blends[m]),
                         mesh.position(vs[2], blends[m]));
  };
  // A triangle in a pixel's order pierces its ray just after now; exactly at now it may not: when
  // its plane holds the eye (det = 0, e.g. a vertex passing through the eye) it covers nothing at
  // that instant (DESIGN.md's strict rule), and its hit is not in front of the eye. That is
  // measure zero, so the front is checked and only then are the other members visited.
  auto pierces = [](double z) { return std::isfinite(z) && z > 0; };
  // Pixel (i, j) whose front does not pierce its ray at now: the nearest member that does, at
  // equal depths the earlier one in the order (the sorted list visits front to back).
  auto nearest_piercing = [&](int i, int j, uint32_t front, std::vector<uint32_t>& members,
                              uint32_t& object_out, uint32_t& prim_out, float& depth_out) {
    const double x = m_scene.column_x(i), y = m_scene.row_y(j);
    uint32_t tri = kNoGridHit;
    double z = 0;
    m_bands->members(i, j, members);
    for (uint32_t other : members) {
      if (other == front) continue;
      const double zo = plane_of(other).depth(x, y);
      if (pierces(zo) && (tri == kNoGridHit || zo < z)) {
        tri = other;
        z = zo;
      }
    }
    if (tri == kNoGridHit) {
      object_out = prim_out = kNoGridHit;
      depth_out = std::numeric_limits<float>::infinity();
      return;
    }
    const uint32_t m = m_scene.mesh_of_triangle(tri);
    object_out = m_scene.mesh(m).id;
    prim_out = tri - m_scene.triangle_begin(m);
    depth_out = float(z);
  };
  // Rows are handed out in blocks: a thread that starts late (the machine is shared) takes fewer,
  // and a block is long enough that the plane cache below is reused from row to row.
  const size_t block_rows =
      std::max<size_t>(kReadoutMinBlockRows, size_t(h) / size_t(kReadoutBlocksPerThread * m_threads));
  const size_t blocks = (size_t(h) + block_rows - 1) / block_rows;
  std::atomic<size_t> next_block{0};
  parallel_chunks(size_t(m_threads), m_threads, [&](size_t, size_t) {
    // The per-pixel loop keeps everything it reads in locals: the buffers' stores could alias
    // anything reached through the captured references, which would then be reloaded per pixel.
    const int width = w;
    std::vector<double> column_x(static_cast<size_t>(width));
    for (int i = 0; i < width; ++i) column_x[size_t(i)] = m_scene.column_x(i);
    const double* xs = column_x.data();
    std::vector<uint32_t> members;
    // A triangle meets a few consecutive rows: the planes of recent rows are kept in a small
    // direct-mapped cache (the same plane_of values, so the same depths bit for bit).
    struct CachedPlane {
      uint32_t tri = kNoGridHit, mesh_id = 0, local = 0;
      TrianglePlane plane{Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()};
    };
    std::vector<CachedPlane> cache_slots(kPlaneCache);
    CachedPlane* cache = cache_slots.data();
    auto fill = [&](CachedPlane& c, uint32_t tri) {
      const uint32_t m = m_scene.mesh_of_triangle(tri);
      const GridMesh& mesh = m_scene.mesh(m);
      c.tri = tri;
      c.mesh_id = mesh.id;
      c.local = tri - m_scene.triangle_begin(m);
      const auto& vs = mesh.triangles[c.local];
      c.plane = TrianglePlane(mesh.position(vs[0], blends[m]), mesh.position(vs[1], blends[m]),
                              mesh.position(vs[2], blends[m]));
    };
    for (size_t b = next_block.fetch_add(1, std::memory_order_relaxed); b < blocks;
         b = next_block.fetch_add(1, std::memory_order_relaxed)) {
      for (size_t j = b * block_rows; j < std::min(size_t(h), (b + 1) * block_rows); ++j) {
        const uint32_t* fronts = m_bands->front_row(int(j));
        uint32_t* object_row = object.data() + j * size_t(width);
        uint32_t* prim_row = prim.data() + j * size_t(width);
        float* depth_row = depth.data() + j * size_t(width);
        const double y = m_scene.row_y(int(j));
        int i = 0;
        while (i < width) {
          // Background comes in long runs (a few per row), filled in bulk.
          int end = i;
          while (end < width && fronts[end] == kNoGridHit) ++end;
          std::fill(object_row + i, object_row + end, kNoGridHit);
          std::fill(prim_row + i, prim_row + end, kNoGridHit);
          std::fill(depth_row + i, depth_row + end, std::numeric_limits<float>::infinity());
          // Covered pixels: a triangle covers only a couple of pixels of a row, so its changes are
          // not branched on; every pixel looks its triangle's plane up in the cache.
          for (i = end; i < width && fronts[i] != kNoGridHit; ++i) {
            const uint32_t tri = fronts[i];
            CachedPlane& c = cache[tri % kPlaneCache];
            if (c.tri != tri) [[unlikely]]
              fill(c, tri);
            const double z = c.plane.depth(xs[i], y);
            if (!pierces(z)) [[unlikely]] {
              nearest_piercing(i, int(j), tri, members, object_row[i], prim_row[i], depth_row[i]);
              continue;
            }
            object_row[i] = c.mesh_id;
            prim_row[i] = c.local;
            depth_row[i] = float(z);
          }
        }
      }
    }
  });
  m_timings.readout += seconds_since(started);
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
