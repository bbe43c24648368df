#include "kinetic/frustum_grid.h"

#include <algorithm>
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
  /// Front triangle (global id or kNoGridHit) of every pixel of rows [row_begin, row_end).
  virtual void fronts(int row_begin, int row_end, std::span<uint32_t> out) const = 0;
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
  BandsOf(const GridScene& scene, int bands, bool audit) : m_width(scene.width()) {
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
  void fronts(int row_begin, int row_end, std::span<uint32_t> out) const override {
    for (int j = row_begin; j < row_end; ++j) {
      static_assert(kNoFront == kNoGridHit);
      const uint32_t* fronts = m_bands[band_of(j)]->front_row(j);
      std::copy(fronts, fronts + m_width, out.begin() + ptrdiff_t(size_t(j - row_begin) * size_t(m_width)));
    }
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
  int m_width;
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
  parallel_chunks(size_t(h), m_threads, [&](size_t row_begin, size_t row_end) {
    m_bands->fronts(int(row_begin), int(row_end),
                    object.subspan(row_begin * size_t(w), (row_end - row_begin) * size_t(w)));
    std::vector<uint32_t> members;
    // A triangle meets a few consecutive rows: the planes of the runs of recent rows are kept in
    // a small direct-mapped cache (the same plane_of values, so the same depths bit for bit).
    struct CachedPlane {
      uint32_t tri = kNoGridHit, mesh_id = 0, local = 0;
      TrianglePlane plane{Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()};
    };
    std::vector<CachedPlane> cache(kPlaneCache);
    for (size_t j = row_begin; j < row_end; ++j) {
      const double y = m_scene.row_y(int(j));
      // A triangle usually covers a run of pixels in a row: its plane is computed once per run.
      uint32_t last = kNoGridHit, mesh_id = 0, local = 0;
      const TrianglePlane* plane = nullptr;
      for (int i = 0; i < w; ++i) {
        const size_t p = j * size_t(w) + size_t(i);
        uint32_t tri = object[p];
        if (tri == kNoGridHit) {
          prim[p] = kNoGridHit;
          depth[p] = std::numeric_limits<float>::infinity();
          continue;
        }
        const double x = m_scene.column_x(i);
        if (tri != last) {
          CachedPlane& c = cache[tri % kPlaneCache];
          if (c.tri != tri) {
            const uint32_t m = m_scene.mesh_of_triangle(tri);
            c.tri = tri;
            c.mesh_id = m_scene.mesh(m).id;
            c.local = tri - m_scene.triangle_begin(m);
            c.plane = plane_of(tri);
          }
          mesh_id = c.mesh_id;
          local = c.local;
          plane = &c.plane;
          last = tri;
        }
        double z = plane->depth(x, y);
        if (!pierces(z)) {
          // The nearest member that pierces the ray at now; at equal depths the earlier one in
          // the order (the sorted list visits front to back).
          const uint32_t front = tri;
          tri = kNoGridHit;
          m_bands->members(i, int(j), members);
          for (uint32_t other : members) {
            if (other == front) continue;
            const double zo = plane_of(other).depth(x, y);
            if (pierces(zo) && (tri == kNoGridHit || zo < z)) {
              tri = other;
              z = zo;
            }
          }
          if (tri == kNoGridHit) {
            object[p] = prim[p] = kNoGridHit;
            depth[p] = std::numeric_limits<float>::infinity();
            continue;
          }
          const uint32_t m = m_scene.mesh_of_triangle(tri);
          object[p] = m_scene.mesh(m).id;
          prim[p] = tri - m_scene.triangle_begin(m);
          depth[p] = float(z);
          continue;
        }
        object[p] = mesh_id;
        prim[p] = local;
        depth[p] = float(z);
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
