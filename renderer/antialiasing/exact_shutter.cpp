#include "renderer/antialiasing/exact_shutter.h"

#include <algorithm>
#include <chrono>
#include <mutex>

#include "renderer/motion_blur/window_pieces.h"
#include "util/parallel.h"

namespace kinray {
namespace {

double seconds_since(std::chrono::steady_clock::time_point& since) {
  const auto now = std::chrono::steady_clock::now();
  const double seconds = std::chrono::duration<double>(now - since).count();
  since = now;
  return seconds;
}

}  // namespace

std::vector<ShutterNode> space_time_nodes(const CameraSpaceScene& scene,
                                          const ShutterWindow& window, const GaussLegendre& rule) {
  if (!(window.close > window.open)) return {{window.time, 1.0}};
  const std::vector<double> breaks = window_breaks(scene, window);
  std::vector<ShutterNode> nodes;
  for (size_t k = 0; k + 1 < breaks.size(); ++k) {
    const double middle = (breaks[k] + breaks[k + 1]) / 2, half = (breaks[k + 1] - breaks[k]) / 2;
    // Gauss-Legendre weights sum to 2 on [-1, 1]: a piece's nodes share half / length each.
    for (size_t n = 0; n < rule.nodes.size(); ++n)
      nodes.push_back({middle + half * rule.nodes[n], rule.weights[n] * half / window.length()});
  }
  // The sets only move forward: the nodes in time order (gauss_legendre lists them from +1 down).
  std::sort(nodes.begin(), nodes.end(),
            [](const ShutterNode& a, const ShutterNode& b) { return a.t < b.t; });
  return nodes;
}

ExactShutter::ExactShutter(const CameraSpaceScene& scene, int order, int threads,
                           MakeSets make_sets)
    : m_scene(scene),
      m_rule(gauss_legendre(order > 0 ? order : kDefaultShutterOrder)),
      m_threads(threads),
      m_make_sets(std::move(make_sets)) {}

void ExactShutter::render(const ShutterWindow& window, Frame& frame) {
  auto clock = std::chrono::steady_clock::now();
  const std::vector<ShutterNode> nodes = space_time_nodes(m_scene, window, m_rule);
  frame.time = window.time;
  const size_t n = frame.pixel_count();
  m_average.assign(n, ColorAverage{});
  const PixelRays image{frame.width, frame.height};
  // The sets hold meshes by their index in the grid's input; its meshes carry their objects.
  const auto to_ref = [this](const SquareTriangle& e) {
    return TriangleRef{m_sets->input().meshes[e.mesh].id, e.triangle};
  };
  std::mutex mutex;
  for (const ShutterNode& node : nodes) {
    // The nodes come in time order; only a window opening before the last one's time (an
    // irregular schedule) takes the sets back, by building them again.
    if (!m_sets || node.t < m_sets->now()) {
      m_stats.rebuilds += m_sets != nullptr;
      m_sets = m_make_sets(node.t);
    }
    m_sets->advance_to(node.t);
    m_stats.events_s += seconds_since(clock);
    parallel_for(size_t(frame.height), m_threads, [&](size_t row) {
      const int j = int(row);
      ExactPixels pixels(m_scene, image, node.t);
      for (int i = 0; i < frame.width; ++i) {
        const size_t p = frame.index(i, j);
        m_average[p].add(pixels.colour(i, j, m_sets->triangles(i, j), to_ref), node.weight);
      }
      const std::lock_guard lock(mutex);
      m_readout += pixels.stats();
    });
    m_stats.readout_s += seconds_since(clock);
  }
  // A pixel whose read-outs are all one colour (nothing moves over its square) keeps it exactly.
  parallel_for(size_t(frame.height), m_threads, [&](size_t row) {
    for (int i = 0; i < frame.width; ++i) {
      const size_t p = frame.index(i, int(row));
      frame.color[p] = m_average[p].result();
    }
  });
  m_stats.readout_s += seconds_since(clock);
  ++m_stats.windows;
  m_stats.nodes += nodes.size();
}

}  // namespace kinray
