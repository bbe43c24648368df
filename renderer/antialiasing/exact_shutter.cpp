#include "renderer/antialiasing/exact_shutter.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <mutex>

#include "renderer/motion_blur/window_pieces.h"
#include "util/parallel.h"
#include "util/stopwatch.h"

namespace kinray {
ExactShutter::ExactShutter(const CameraSpaceScene& scene, const Config& config, int threads,
                           MakeSets make_sets)
    : m_scene(scene),
      m_config(config),
      m_threads(threads),
      m_make_sets(std::move(make_sets)),
      m_fixed_fov(scene.fixed_tan_half_fov().has_value()) {
  for (const CameraSpaceObject& cs : scene.objects) m_moves.push_back(moves(cs));
  const int order = config.order > 0 ? config.order : kDefaultShutterOrder;
  for (int nodes = 1; nodes <= order; ++nodes) m_rules.push_back(gauss_legendre(nodes));
}

void ExactShutter::render(const ShutterWindow& window, Frame& frame) {
  auto clock = std::chrono::steady_clock::now();
  frame.time = window.time;
  const double open = window.open, close = std::max(window.close, window.open);
  // The sets at the open time, then through the window with the log on: one advance, every
  // event in time order. Only a window opening before the sets' time takes them back.
  if (!m_sets || m_sets->now() > open) {
    m_stats.rebuilds += m_sets != nullptr;
    m_sets = m_make_sets(open);
  }
  m_sets->log_changes(false);
  m_sets->advance_to(open);
  m_sets->clear_changes();
  m_sets->log_changes(true);
  m_sets->advance_to(close);
  m_sets->log_changes(false);
  const SquareChangeLog& log = m_sets->changes();
  // The log by pixel, each pixel's changes in time order (a stable counting sort).
  const size_t n = frame.pixel_count();
  m_change_begin.assign(n + 1, 0);
  for (const SquareChange& c : log) ++m_change_begin[c.pixel + 1];
  for (size_t p = 0; p < n; ++p) m_change_begin[p + 1] += m_change_begin[p];
  m_change_order.resize(log.size());
  {
    std::vector<uint32_t> next(m_change_begin.begin(), m_change_begin.end() - 1);
    for (size_t k = 0; k < log.size(); ++k) m_change_order[next[log[k].pixel]++] = uint32_t(k);
  }
  m_stats.events_s += lap_seconds(clock);

  const std::vector<double> breaks = window_breaks(m_scene, window);
  const auto rule_of = [&](size_t nodes) -> const GaussLegendre& { return m_rules[nodes - 1]; };
  const bool long_window = close > open;
  const PixelRays image{frame.width, frame.height};
  const GridInput& input = m_sets->input();
  const auto to_ref = [&](const SquareTriangle& e) {
    return TriangleRef{input.meshes[e.mesh].id, e.triangle};
  };
  std::atomic<uint64_t> readouts{0}, pieces{0}, still{0};
  std::mutex mutex;
  parallel_for(size_t(frame.height), m_threads, [&](size_t row) {
    const int j = int(row);
    ExactPixels pixels(m_scene, image, window.time);
    std::vector<SquareTriangle> set;
    std::vector<double> cuts;
    uint64_t row_readouts = 0, row_pieces = 0, row_still = 0;
    for (int i = 0; i < frame.width; ++i) {
      const size_t p = frame.index(i, j);
      // Every triangle over the square at some time of the window.
      const std::span<const SquareTriangle> at_close = m_sets->triangles(i, j);
      set.assign(at_close.begin(), at_close.end());
      for (uint32_t k = m_change_begin[p]; k < m_change_begin[p + 1]; ++k)
        set.push_back(log[m_change_order[k]].triangle);
      cuts.clear();
      if (m_config.cut_at_events)
        for (int dj = -1; dj <= 1; ++dj)
          for (int di = -1; di <= 1; ++di) {
            const int qi = i + di, qj = j + dj;
            if (qi < 0 || qj < 0 || qi >= frame.width || qj >= frame.height) continue;
            const size_t q = frame.index(qi, qj);
            for (uint32_t k = m_change_begin[q]; k < m_change_begin[q + 1]; ++k) {
              const SquareChange& c = log[m_change_order[k]];
              if (!(c.time > open && c.time < close)) continue;
              if (q == p || std::find(set.begin(), set.end(), c.triangle) != set.end())
                cuts.push_back(c.time);
            }
          }
      std::sort(cuts.begin(), cuts.end());
      cuts.erase(std::unique(cuts.begin(), cuts.end()), cuts.end());
      // Nothing over the square moves, appears or changes (a triangle appearing or disappearing
      // enters or leaves the set, which the log holds): g is constant, one read-out.
      const bool still_pixel =
          !long_window || (m_fixed_fov && m_change_begin[p] == m_change_begin[p + 1] &&
                           std::none_of(set.begin(), set.end(), [&](const SquareTriangle& e) {
                             return m_moves[input.meshes[e.mesh].id] != 0;
                           }));
      if (still_pixel) {
        pixels.set_time(window.time);
        frame.color[p] = pixels.colour(i, j, std::span<const SquareTriangle>(set), to_ref);
        ++row_readouts;
        ++row_pieces;
        ++row_still;
        continue;
      }
      ColorAverage average;
      // `nodes` Gauss-Legendre nodes over [a, b].
      const auto integrate = [&](double a, double b, size_t nodes) {
        const GaussLegendre& rule = rule_of(nodes);
        const double middle = (a + b) / 2, half = (b - a) / 2;
        // Gauss-Legendre weights sum to 2: a piece's nodes share half / length of the window.
        for (size_t node = 0; node < rule.nodes.size(); ++node) {
          pixels.set_time(middle + half * rule.nodes[node]);
          average.add(pixels.colour(i, j, std::span<const SquareTriangle>(set), to_ref),
                      rule.weights[node] * half / (close - open));
        }
        row_readouts += rule.nodes.size();
        ++row_pieces;
      };
      const size_t order = m_rules.size();
      // The nodes of a part of [a, b] that has `nodes` of them: in proportion to its length
      // (rounded up, less the rounding of the lengths: half of four nodes is two), at least
      // `least`.
      const auto share = [](size_t nodes, double from, double to, double a, double b,
                            size_t least) {
        const double exact = double(nodes) * (to - from) / (b - a);
        return std::clamp<size_t>(size_t(std::ceil(exact - 1e-9)), std::min(least, nodes), nodes);
      };
      auto cut = cuts.begin();
      for (size_t k = 0; k + 1 < breaks.size(); ++k) {
        const double a = breaks[k], b = breaks[k + 1];
        // The window's `order` nodes shared by its pieces of the motion (g is smooth in each,
        // and a piece much shorter than the window needs fewer), at least two each (exact for
        // cubics): many short pieces make a composite rule.
        const size_t nodes = share(order, a, b, open, close, 2);
        const auto first = cut;
        while (cut != cuts.end() && *cut < b) ++cut;
        const size_t inside = size_t(cut - first);
        // A piece with no event, or more events than nodes (many small turns of g, which one
        // rule averages), takes its rule whole. Else each part between the events is smooth and
        // takes the piece's nodes in proportion to its length, at least one: at most `inside`
        // read-outs more than the piece's rule.
        if (inside == 0 || inside > nodes) {
          integrate(a, b, nodes);
          continue;
        }
        double from = a;
        for (auto c = first; c <= cut; ++c) {
          const double to = c == cut ? b : *c;
          integrate(from, to, share(nodes, from, to, a, b, 1));
          from = to;
        }
      }
      // A pixel whose read-outs are all one colour keeps it exactly.
      frame.color[p] = average.result();
    }
    readouts.fetch_add(row_readouts, std::memory_order_relaxed);
    pieces.fetch_add(row_pieces, std::memory_order_relaxed);
    still.fetch_add(row_still, std::memory_order_relaxed);
    const std::lock_guard lock(mutex);
    m_readout += pixels.stats();
  });
  m_stats.readout_s += lap_seconds(clock);
  ++m_stats.windows;
  m_stats.readouts += readouts.load();
  m_stats.pieces += pieces.load();
  m_stats.still_pixels += still.load();
  m_stats.changes += log.size();
}

}  // namespace kinray
