// TreeBenchReport: JSON, a readable table and the charts of `kinray bench --structure ...`.
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <map>
#include <ostream>

#include "verification/chart.h"
#include "verification/tree_benchmark.h"

namespace kinray {

nlohmann::json TreeBenchReport::to_json() const {
  nlohmann::json out = nlohmann::json::array();
  for (const TreeBenchPoint& p : points)
    out.push_back({{"sweep", p.sweep},
                   {"scene", p.scene},
                   {"tree", p.tree},
                   {"inbetweens", p.inbetweens},
                   {"triangles", p.triangles},
                   {"frames", p.frames},
                   {"key_intervals", p.key_intervals},
                   {"events_per_interval", p.events_per_interval},
                   {"failures_per_interval", p.failures_per_interval},
                   {"certificates_per_interval", p.certificates_per_interval},
                   {"bv_updates_per_interval", p.bv_updates_per_interval},
                   {"kinetic_update_ms_per_frame", p.kinetic_update_ms_per_frame},
                   {"bottom_up_update_ms_per_frame", p.bottom_up_update_ms_per_frame},
                   {"embree_refit_update_ms_per_frame", p.embree_refit_update_ms_per_frame},
                   {"embree_rebuild_update_ms_per_frame", p.embree_rebuild_update_ms_per_frame},
                   {"update_speedup", p.update_speedup},
                   {"shadow_rays_per_frame", p.shadow_rays_per_frame},
                   {"shadow_ms_per_frame", p.shadow_ms_per_frame},
                   {"bottom_up_shadow_ms_per_frame", p.bottom_up_shadow_ms_per_frame},
                   {"embree_refit_shadow_ms_per_frame", p.embree_refit_shadow_ms_per_frame},
                   {"embree_rebuild_shadow_ms_per_frame", p.embree_rebuild_shadow_ms_per_frame},
                   {"total_ms_per_frame", p.total_ms_per_frame},
                   {"bottom_up_total_ms_per_frame", p.bottom_up_total_ms_per_frame},
                   {"embree_refit_total_ms_per_frame", p.embree_refit_total_ms_per_frame},
                   {"embree_rebuild_total_ms_per_frame", p.embree_rebuild_total_ms_per_frame},
                   {"build_ms", p.build_ms},
                   {"embree_mask_mismatches", p.embree_mask_mismatches},
                   {"stats", p.stats}});
  return {{"structure_points", out}};
}

void TreeBenchReport::print(std::ostream& out) const {
  out << std::left << std::setw(11) << "sweep" << std::setw(8) << "tree" << std::right
      << std::setw(5) << "K" << std::setw(9) << "tris" << std::setw(12) << "events/int"
      << std::setw(12) << "BV upd/int" << std::setw(10) << "kin upd" << std::setw(10) << "b-up upd"
      << std::setw(8) << "speedup" << std::setw(10) << "refit upd" << std::setw(10) << "rebuild"
      << std::setw(10) << "total" << std::setw(10) << "b-up tot" << std::setw(10) << "refit tot"
      << std::setw(10) << "rebld tot"
      << "   (ms per frame)\n";
  out << std::fixed;
  for (const TreeBenchPoint& p : points)
    out << std::left << std::setw(11) << p.sweep << std::setw(8) << p.tree << std::right
        << std::setw(5) << p.inbetweens << std::setw(9) << p.triangles << std::setprecision(0)
        << std::setw(12) << p.events_per_interval << std::setw(12) << p.bv_updates_per_interval
        << std::setprecision(3) << std::setw(10) << p.kinetic_update_ms_per_frame << std::setw(10)
        << p.bottom_up_update_ms_per_frame << std::setprecision(1) << std::setw(8)
        << p.update_speedup << std::setprecision(3) << std::setw(10)
        << p.embree_refit_update_ms_per_frame << std::setw(10)
        << p.embree_rebuild_update_ms_per_frame << std::setw(10) << p.total_ms_per_frame
        << std::setw(10) << p.bottom_up_total_ms_per_frame << std::setw(10)
        << p.embree_refit_total_ms_per_frame << std::setw(10) << p.embree_rebuild_total_ms_per_frame
        << "\n";
  out.unsetf(std::ios::fixed);
}

std::vector<std::string> TreeBenchReport::write_charts(const std::string& folder) const {
  std::filesystem::create_directories(folder);
  const std::vector<Color> palette = {{0.85f, 0.33f, 0.1f},  {0.47f, 0.67f, 0.19f},
                                      {0.0f, 0.45f, 0.74f},  {0.49f, 0.18f, 0.56f},
                                      {0.64f, 0.08f, 0.18f}, {0.5f, 0.5f, 0.5f}};
  std::map<std::string, std::vector<const TreeBenchPoint*>> sweeps;
  for (const TreeBenchPoint& p : points) sweeps[p.sweep].push_back(&p);
  std::vector<std::string> written;
  for (const auto& [sweep_name, sweep_points] : sweeps) {
    const std::string& sweep = sweep_name;  // clang 14's lambdas cannot capture a binding
    const bool by_k = sweep == "inbetweens";
    auto x_of = [&](const TreeBenchPoint& p) {
      return by_k ? double(p.inbetweens) : double(p.triangles);
    };
    const std::string x_label = by_k ? "in-betweens per keyframe interval" : "triangles";
    const std::string scene =
        sweep_points.front()->scene.substr(0, sweep_points.front()->scene.find(':'));
    std::map<std::string, ChartSeries> events, update, total;
    auto add = [&](std::map<std::string, ChartSeries>& chart, const std::string& label,
                   size_t color, bool dashed, double x, double y) {
      ChartSeries& s = chart[label];
      s.label = label;
      s.color = palette[color % palette.size()];
      s.dashed = dashed;
      s.x.push_back(x);
      s.y.push_back(y);
    };
    size_t tree_index = 0;
    std::map<std::string, size_t> tree_colors;
    for (const TreeBenchPoint* p : sweep_points) {
      if (!tree_colors.count(p->tree)) tree_colors[p->tree] = tree_index++;
      const size_t c = tree_colors[p->tree];
      const double x = x_of(*p);
      add(events, "kinetic " + p->tree + " events", c, false, x, p->events_per_interval);
      add(update, "kinetic " + p->tree, c, false, x, p->kinetic_update_ms_per_frame);
      add(total, "kinetic " + p->tree, c, false, x, p->total_ms_per_frame);
      if (c != 0) continue;  // the peers once per configuration
      add(events, "bottom-up BV updates", 2, true, x, p->bv_updates_per_interval);
      if (!by_k) {  // the n log n reference through the first point
        const TreeBenchPoint& f = *sweep_points.front();
        const double n0 = double(f.triangles), n = double(p->triangles);
        add(events, "n log n", 5, true, x,
            f.events_per_interval * n * std::log(n) / (n0 * std::log(n0)));
      }
      add(update, "bottom-up", 2, true, x, p->bottom_up_update_ms_per_frame);
      add(update, "embree refit", 3, true, x, p->embree_refit_update_ms_per_frame);
      add(update, "embree rebuild", 4, true, x, p->embree_rebuild_update_ms_per_frame);
      add(total, "bottom-up", 2, true, x, p->bottom_up_total_ms_per_frame);
      add(total, "embree refit", 3, true, x, p->embree_refit_total_ms_per_frame);
      add(total, "embree rebuild", 4, true, x, p->embree_rebuild_total_ms_per_frame);
    }
    auto write = [&](const std::string& name, const std::string& title, const std::string& y_label,
                     std::map<std::string, ChartSeries>& series) {
      Chart chart;
      chart.title = title + ": " + scene;
      chart.x_label = x_label;
      chart.y_label = y_label;
      chart.log_x = chart.log_y = true;
      for (auto& [label, s] : series) chart.series.push_back(s);
      const std::string path =
          (std::filesystem::path(folder) / ("trees_" + sweep + "_" + name + ".png")).string();
      write_chart_png(chart, path);
      written.push_back(path);
    };
    write("events", "Events and BV updates per keyframe interval", "per interval", events);
    write("update", "Update time per frame", "ms per frame", update);
    write("total", "Total time per frame with shadow rays", "ms per frame", total);
  }
  return written;
}

}  // namespace kinray
