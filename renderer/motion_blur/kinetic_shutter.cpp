#include "renderer/motion_blur/kinetic_shutter.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <limits>

#include "renderer/motion_blur/texture_path.h"
#include "renderer/plane_depth.h"
#include "renderer/shading.h"
#include "util/parallel.h"
#include "util/stopwatch.h"

namespace kinray {

KineticShutter::KineticShutter(const CameraSpaceScene& scene, int order, int threads,
                               const CameraSpaceLights* lights)
    : m_scene(scene),
      m_rule(gauss_legendre(order > 0 ? order : kDefaultShutterOrder)),
      m_threads(threads),
      m_fixed_tan_half_fov(scene.fixed_tan_half_fov()) {
  const int base = int(m_rule.nodes.size());
  m_textured_rule = base >= kTexturedShutterOrder ? m_rule : gauss_legendre(kTexturedShutterOrder);
  for (const CameraSpaceObject& cs : scene.objects)
    m_textured.push_back(shading_texture(*scene.scene, scene.scene->objects[cs.object]) != nullptr);
  if (lights != nullptr && !lights->empty())
    m_shadows = std::make_unique<ShutterShadows>(scene, *lights, m_rule);
}

void KineticShutter::start_logging(FrustumGrid& grid) {
  if (!m_started) {
    // The fronts at the grid's time, and from now on every change is logged.
    const GridScene& scene = grid.scene();
    m_open_front.assign(size_t(scene.width()) * size_t(scene.height()), kNoGridHit);
    for (int j = 0; j < scene.height(); ++j)
      for (int i = 0; i < scene.width(); ++i)
        if (const auto hit = grid.front(i, j))
          m_open_front[size_t(j) * size_t(scene.width()) + size_t(i)] =
              scene.triangle_begin(hit->mesh) + hit->triangle;
    grid.log_front_changes(true);
    m_started = true;
  }
}

void KineticShutter::roll_to(FrustumGrid& grid, double open) {
  for (FrontChangeLog& log : grid.front_logs()) {
    auto& changes = log.changes;
    const auto end = std::find_if(changes.begin(), changes.end(),
                                  [&](const FrontChange& c) { return c.time > open; });
    for (auto c = changes.begin(); c != end; ++c) m_open_front[c->pixel] = c->front;
    changes.erase(changes.begin(), end);
  }
}

template <class Visit>
void KineticShutter::for_each_node(uint32_t object, double t0, double t1, double length,
                                   Visit&& visit) const {
  for_each_quadrature_node(m_scene.objects[object].key_times, rule(object), t0, t1, length, visit);
}

void KineticShutter::place_window_nodes(const ShutterWindow& window) {
  m_window = window;
  m_window_nodes.resize(m_scene.objects.size());
  for (uint32_t object = 0; object < m_window_nodes.size(); ++object) {
    std::vector<WindowNode>& nodes = m_window_nodes[object];
    nodes.clear();
    if (!(window.close > window.open)) continue;
    for_each_node(object, window.open, window.close, window.length(),
                  [&](double t, double w, size_t next) {
                    nodes.push_back({instant(object, t, next), w});
                  });
  }
}

ShadingInstant KineticShutter::instant(uint32_t object, double t, size_t next) const {
  return {locate(m_scene.objects[object].key_times, t, next),
          m_fixed_tan_half_fov ? *m_fixed_tan_half_fov : m_scene.tan_half_fov(t)};
}

void KineticShutter::integrate(const GridScene& grid, uint32_t front, int i, int j, double t0,
                               double t1, double length, SegmentCache& cache,
                               ShutterShadowCounts& counts, ColorAverage& average) const {
  if (!(t1 > t0)) return;
  if (front == kNoGridHit) {
    average.add(kBackgroundColor, (t1 - t0) / length);
    return;
  }
  const uint32_t m = grid.mesh_of_triangle(front);
  const uint32_t object = grid.mesh(m).id, prim = front - grid.triangle_begin(m);
  const Vec3 d = PixelRays{grid.width(), grid.height()}.direction(i, j);
  if (m_shadows) {
    m_shadows->integrate(object, prim, d, t0, t1, rule(object), average, counts);
    return;
  }
  ViewCache view;
  if (m_textured[object]) {
    // Each node shows its texture's mean over its cell (texture_path.h).
    TexturePath texture(m_scene, object, prim, d);
    for_each_quadrature_cell(
        m_scene.objects[object].key_times, rule(object), t0, t1, length,
        [&](double t, double w, size_t next, double lo, double hi) {
          const ShadingInstant at = instant(object, t, next);
          const TriangleAtInstant triangle = cache.get(m_scene, object, prim, at.segment.k).at(at);
          SurfacePoint surface = surface_point(triangle, d, view.at(d, triangle.tan_half_fov));
          surface.base = texture.base(lo, hi);
          ++counts.shading_nodes;
          average.add(headlight_color(surface), w);
        });
    return;
  }
  for_each_node(object, t0, t1, length, [&](double t, double w, size_t next) {
    const ShadingInstant at = instant(object, t, next);
    const TriangleAtInstant triangle = cache.get(m_scene, object, prim, at.segment.k).at(at);
    ++counts.shading_nodes;
    average.add(headlight_color(triangle, d, view.at(d, triangle.tan_half_fov)), w);
  });
}

void KineticShutter::integrate_window(const GridScene& grid, uint32_t front, int i, int j,
                                      FrontNodes& memo, SegmentCache& cache,
                                      ShutterShadowCounts& counts, ColorAverage& average) const {
  if (front == kNoGridHit) {
    average.add(kBackgroundColor, 1.0);
    return;
  }
  const uint32_t m = grid.mesh_of_triangle(front);
  const uint32_t object = grid.mesh(m).id, prim = front - grid.triangle_begin(m);
  if (m_textured[object]) {
    // Its nodes' textures are averaged over cells of the pixel's own path: nothing to share.
    integrate(grid, front, i, j, m_window.open, m_window.close, m_window.length(), cache, counts,
              average);
    return;
  }
  const std::vector<WindowNode>& nodes = m_window_nodes[object];
  if (memo.front != front) {
    memo.front = front;
    memo.triangles.clear();
    for (const WindowNode& node : nodes)
      memo.triangles.push_back(
          cache.get(m_scene, object, prim, node.instant.segment.k).at(node.instant));
  }
  const Vec3 d = PixelRays{grid.width(), grid.height()}.direction(i, j);
  ViewCache view;
  counts.shading_nodes += nodes.size();
  for (size_t k = 0; k < nodes.size(); ++k) {
    const TriangleAtInstant& triangle = memo.triangles[k];
    average.add(headlight_color(triangle, d, view.at(d, triangle.tan_half_fov)), nodes[k].weight);
  }
}

void KineticShutter::render(FrustumGrid& grid, const ShutterWindow& window, Frame& frame) {
  auto clock = std::chrono::steady_clock::now();
  start_logging(grid);
  // One advance through the gap since the last window and this window: each band runs its
  // events to the close in one go, and the log says where the fronts were at the open.
  grid.advance_to(std::max(window.close, grid.now()));
  roll_to(grid, window.open);
  if (m_shadows) m_shadows->begin_window(window);
  m_stats.events_s += lap_seconds(clock);
  const GridScene& scene = grid.scene();
  const int w = scene.width(), h = scene.height();
  const size_t n = size_t(w) * size_t(h);
  if (frame.width != w || frame.height != h) frame.resize(w, h);
  frame.time = window.time;
  const double length = window.length();
  place_window_nodes(window);

  // Each band's log touches only its own rows' pixels, so the logs are walked in parallel: each
  // change closes the pixel's current interval and opens the next. A pixel's open interval and
  // its average so far live in one SplitPixel (one cache line), made at its first change: the
  // changes come in time order, at pixels all over the band, and five per-pixel arrays were five
  // cache misses per change. Band b's SplitPixels take the slots from its offset on (a band has
  // at most as many split pixels as changes).
  const std::span<FrontChangeLog> logs = grid.front_logs();
  std::vector<size_t> offset(logs.size() + 1, 0);
  for (size_t b = 0; b < logs.size(); ++b) offset[b + 1] = offset[b] + logs[b].changes.size();
  if (m_split.size() < offset.back()) m_split.resize(offset.back());
  if (m_split_index.size() != n) {
    m_split_index.assign(n, kNotSplit);
    m_split_at_time.assign(n, kNoGridHit);
  }
  std::vector<size_t> split_end(offset.begin(), offset.end() - 1);
  std::atomic<uint64_t> changes{0}, nodes{0}, rays{0}, mask_changes{0};
  const auto add_counts = [&](const ShutterShadowCounts& c) {
    nodes.fetch_add(c.shading_nodes, std::memory_order_relaxed);
    rays.fetch_add(c.shadow_rays, std::memory_order_relaxed);
    mask_changes.fetch_add(c.mask_changes, std::memory_order_relaxed);
  };
  parallel_for_dynamic(logs.size(), m_threads, [&](size_t b) {
    SegmentCache cache;
    ShutterShadowCounts band_counts;
    size_t& end = split_end[b];
    for (const FrontChange& c : logs[b].changes) {
      if (c.time > window.close) break;
      const size_t p = c.pixel;
      const int i = int(p % size_t(w)), j = int(p / size_t(w));
      uint32_t& index = m_split_index[p];
      if (index == kNotSplit) {
        index = uint32_t(end);
        m_split[end++] = SplitPixel{ColorAverage{}, window.open, m_open_front[p], m_open_front[p]};
      }
      SplitPixel& s = m_split[index];
      integrate(scene, s.front, i, j, s.since, c.time, length, cache, band_counts, s.average);
      s.front = c.front;
      s.since = c.time;
      if (c.time <= window.time) s.at_time = c.front;
    }
    changes.fetch_add(logs[b].changes.size(), std::memory_order_relaxed);
    add_counts(band_counts);
  });
  const PixelRays image{w, h};
  parallel_for(size_t(h), m_threads, [&](size_t row) {
    const int j = int(row);
    FrontNodes memo;  // neighbours along a row mostly share their front
    SegmentCache cache;
    ShutterShadowCounts row_counts;
    for (int i = 0; i < w; ++i) {
      const size_t p = size_t(j) * size_t(w) + size_t(i);
      const uint32_t index = m_split_index[p];
      if (index != kNotSplit) {
        SplitPixel& s = m_split[index];
        integrate(scene, s.front, i, j, s.since, window.close, length, cache, row_counts,
                  s.average);
        frame.color[p] = s.average.result();
        m_split_at_time[p] = s.at_time;  // for the read-out, in pixel order
        continue;
      }
      // A window of length zero has no intervals: its pixels average nothing.
      ColorAverage average;
      if (window.close > window.open) {
        if (m_shadows)  // the window's nodes are not shared: each pixel's masks are its own
          integrate(scene, m_open_front[p], i, j, window.open, window.close, length, cache,
                    row_counts, average);
        else
          integrate_window(scene, m_open_front[p], i, j, memo, cache, row_counts, average);
      }
      frame.color[p] = average.result();
    }
    add_counts(row_counts);
  });
  m_stats.integrate_s += lap_seconds(clock);
  // The id and depth buffers: the front at the frame time, as the sharp frame has it; with
  // lights, its light mask there too.
  if (m_shadows) frame.lit.assign(n, 0u);
  parallel_for(size_t(h), m_threads, [&](size_t row) {
    const int j = int(row);
    for (int i = 0; i < w; ++i) {
      const size_t p = size_t(j) * size_t(w) + size_t(i);
      uint32_t front = m_open_front[p];
      if (uint32_t& index = m_split_index[p]; index != kNotSplit) {
        front = m_split_at_time[p];
        index = kNotSplit;  // free for the next window
      }
      if (front == kNoGridHit) {
        frame.object[p] = frame.prim[p] = kNoHit;
        frame.depth[p] = std::numeric_limits<float>::infinity();
        continue;
      }
      const uint32_t m = scene.mesh_of_triangle(front);
      frame.object[p] = scene.mesh(m).id;
      frame.prim[p] = front - scene.triangle_begin(m);
      frame.depth[p] = exact_plane_depth(m_scene, frame.object[p], frame.prim[p],
                                         image.direction(i, j), window.time);
      if (m_shadows)
        frame.lit[p] =
            m_shadows->mask_at(frame.object[p], frame.prim[p], image.direction(i, j), window.time);
    }
  });
  uint64_t split_count = 0;
  for (size_t b = 0; b < logs.size(); ++b) split_count += split_end[b] - offset[b];
  m_stats.front_changes += changes.load();
  m_stats.pixels_split += split_count;
  m_stats.shading_nodes += nodes.load();
  m_stats.shadow_rays += rays.load();
  m_stats.mask_changes += mask_changes.load();
  m_stats.readout_s += lap_seconds(clock);
}

}  // namespace kinray
