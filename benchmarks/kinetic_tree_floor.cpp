// How far the kinetic AABB tree's key interval is from a floor, against the bottom-up update it is
// compared with (the target: the update 10x faster than bottom-up at 16 in-betweens per key
// interval, 50x at 128). A flightplan update changes every vertex's motion, so at each key every
// certificate of the moving meshes is decided again on the new segment, and between keys every
// certificate failure is an event. The floor keeps only that work:
//  - keys:   one comparison per certificate at the segment's end key (a certificate that holds at
//            the key it starts from and at its end key holds in between: the motion is linear),
//            with the tree's realizers and competitors laid out flat in pass order and the end
//            key's coordinates per axis: no bookkeeping, no failure times, no tree walk;
//  - events: per event one queue pop, then per side the tree recomputes for it (the failed side
//            and its climb, as many as the tree's own count) one certificate built from its two
//            vertices' motions, its failure time and a queue update (the tree's EventQueue,
//            holding one interval's events); one certificate where a leaf side computes two;
// and one bottom-up update (vertex blends, leaf boxes, parents) is what each frame of the baseline
// costs. It measures the three on wavy-sphere (100,000 triangles by default, as in the target; the
// scene, time and camera of `kinray bench wavy-sphere:triangles=N --structure aabb`) with the
// kinetic tree's real key interval (its key pass and the events up to the next key), and prints
// what the floor would allow at K in-betweens, K * bottom-up pass / (keys + events), beside the
// tree's own K * pass / interval. The floor is not a proof about every implementation (a leaner
// queue or layout moves it); it shows how much of an interval is the work itself.
//
//   build/bin/bench_kinetic_tree_floor [--benchmark_repetitions=5] [--triangles=N]
//
// One thread; the summary takes each benchmark's median when repeated.

#include <benchmark/benchmark.h>

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <exception>
#include <map>
#include <memory>
#include <random>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "kinetic/core/event_queue.h"
#include "kinetic/tree/bottom_up_bvh.h"
#include "kinetic/tree/kinetic_bvh.h"
#include "renderer/backends/grid_meshes.h"
#include "renderer/job/render_job.h"

namespace {

using namespace kinray;

int g_triangles = 100000;

/// The scene, the tree on a key's segment, and its certificates at the key laid out flat.
struct Floor {
  std::unique_ptr<RenderJob> job;
  std::vector<FlightplanMesh> meshes;
  std::unique_ptr<KineticBvh> tree;
  std::unique_ptr<BottomUpBvh> bottom_up;
  double key = 0, next_key = 0, after_next_key = 0;  ///< the tree's segment, and the next
  /// One record per certificate, in the key pass's order (children before parents): the
  /// realizer, its competitor, the axis and the side's sign.
  std::vector<uint32_t> realizer, competitor;
  std::vector<uint8_t> axis;
  std::vector<double> sign;
  std::array<std::vector<double>, 3> end;  ///< per axis, every vertex at the segment's end key
  double margin = 0;
  uint64_t events_per_interval = 0;
  /// Sides recomputed per event (update_side: the failed side, then its parents while their
  /// realizers change, and the first that keeps its own), each a certificate and a queue update.
  double updates_per_event = 0;
};

Floor& floor_setup() {
  static std::unique_ptr<Floor> setup;
  if (setup) return *setup;
  setup = std::make_unique<Floor>();
  Floor& f = *setup;
  RenderParams params;
  params.scene = "wavy-sphere:triangles=" + std::to_string(g_triangles);
  params.time = std::make_pair(0.0, 0.25);
  params.inbetweens = 1;
  params.backend = "embree";
  params.quiet = true;
  f.job = std::make_unique<RenderJob>(params);
  f.meshes = grid_meshes(f.job->camera_space());
  // The tree on the segment from the shot's second key, and the events of that whole segment.
  const std::span<const double> keys = f.meshes.front().key_times;
  if (keys.size() < 4)
    throw std::runtime_error("bench_kinetic_tree_floor: the scene has fewer than four keys");
  f.key = keys[1];
  f.next_key = keys[2];
  f.after_next_key = keys[3];
  f.tree = std::make_unique<KineticBvh>(f.meshes, f.key, KineticBvh::Config{});
  f.bottom_up = std::make_unique<BottomUpBvh>(f.meshes, f.key);
  const KineticBvh& tree = *f.tree;
  const TreeMeshes& m = tree.meshes();
  for (int a = 0; a < 3; ++a) {
    f.end[size_t(a)].resize(m.vertex_count());
    for (uint32_t v = 0; v < m.vertex_count(); ++v) f.end[size_t(a)][v] = m.key_end(v)[a];
  }
  f.margin = tree.key_margin();
  const BvhTopology& topology = tree.topology();
  for (uint32_t i = uint32_t(topology.nodes.size()); i-- > 0;) {
    const BvhNode& n = topology.nodes[i];
    for (int s = 0; s < 6; ++s) {
      const uint32_t r = tree.realizer(i, s);
      if (r == kNoVertex) continue;
      auto add = [&](uint32_t q) {
        if (q == r || q == kNoVertex) return;
        f.realizer.push_back(r);
        f.competitor.push_back(q);
        f.axis.push_back(uint8_t(side_axis(s)));
        f.sign.push_back(side_sign(s));
      };
      if (n.leaf()) {
        for (uint32_t q : m.triangle(n.triangle)) add(q);
      } else {
        const uint32_t l = tree.realizer(n.left, s), q = tree.realizer(n.right, s);
        if (l != q) add(r == l ? q : l);
      }
    }
  }
  if (f.realizer.empty())
    throw std::runtime_error("bench_kinetic_tree_floor: the tree has no certificate");
  // The events of the whole segment, from the same tree (its segment and the certificates above
  // stay those of the key: no key is crossed).
  const TreeStats before = f.tree->stats();
  f.tree->advance_to(std::nextafter(f.next_key, 0.0));
  const TreeStats after = f.tree->stats();
  f.events_per_interval = after.events.total() - before.events.total();
  f.updates_per_event = double(after.certificates_computed - before.certificates_computed) /
                        double(std::max<uint64_t>(1, f.events_per_interval));
  return f;
}

/// One bottom-up update (what each frame of the baseline costs).
void BM_BottomUpPass(benchmark::State& state) {
  Floor& f = floor_setup();
  double t = f.key;
  const double step = (f.next_key - f.key) / 64;
  for (auto _ : state) {
    t = t + step < f.next_key ? t + step : f.key;
    f.bottom_up->update(t);
    benchmark::ClobberMemory();
  }
  state.counters["nodes"] = double(f.bottom_up->topology().nodes.size());
}

/// Every certificate compared once at the end key, with no bookkeeping and no tree walk.
void BM_FloorKeyComparisons(benchmark::State& state) {
  Floor& f = floor_setup();
  const size_t n = f.realizer.size();
  const uint32_t* r = f.realizer.data();
  const uint32_t* q = f.competitor.data();
  const uint8_t* axis = f.axis.data();
  const double* sign = f.sign.data();
  const double* end[3] = {f.end[0].data(), f.end[1].data(), f.end[2].data()};
  const double margin = f.margin;
  uint64_t held = 0;
  for (auto _ : state) {
    held = 0;
    for (size_t k = 0; k < n; ++k) {
      const double* e = end[axis[k]];
      held += sign[k] * (e[r[k]] - e[q[k]]) > margin;
    }
    benchmark::DoNotOptimize(held);
  }
  state.counters["certificates"] = double(n);
  state.counters["held_by_margin"] = double(held) / double(n);
}

/// One interval's events at their least: per event one pop, then as many sides recomputed as the
/// tree recomputes per event (the failed side and the climb), each one certificate built from its
/// two vertices' motions, its failure time and a queue update (all on the event's own new entry,
/// which stays in cache: the tree's climb moves its parents' entries, wherever they are).
void BM_FloorEvents(benchmark::State& state) {
  Floor& f = floor_setup();
  const TreeMeshes& m = f.tree->meshes();
  const size_t events = f.events_per_interval, n = f.realizer.size();
  std::mt19937_64 rng(15);
  std::uniform_real_distribution<double> when(f.key, f.next_key);
  std::uniform_int_distribution<size_t> which(0, n - 1);
  std::vector<size_t> sides(events * 4);
  for (size_t& s : sides) s = which(rng);
  std::vector<double> times(events);
  for (double& t : times) t = when(rng);
  std::sort(times.begin(), times.end());
  // The updates of each event: the fractional count spread evenly (at most four an event, as
  // `sides` holds; wavy-sphere recomputes 3.37).
  std::vector<uint8_t> updates(events);
  double owed = 0;
  for (uint8_t& u : updates) {
    owed += f.updates_per_event;
    u = uint8_t(std::clamp(std::floor(owed), 1.0, 4.0));
    owed -= u;
  }
  for (auto _ : state) {
    state.PauseTiming();
    EventQueue queue;
    // The queue holds what the tree's does: the certificates failing in the segment.
    for (size_t k = 0; k < events; ++k) queue.push(EventKey{times[k], 1, uint32_t(k), 0}, k);
    state.ResumeTiming();
    double failures = 0;
    for (size_t handled = 0; handled < events; ++handled) {
      const EventKey key = queue.top_key();
      const size_t k = size_t(queue.top_payload());
      queue.pop();
      EventHandle h = kNoEvent;
      for (uint8_t u = 0; u < updates[k]; ++u) {
        const size_t s = sides[4 * k + u];
        const LinearCertificate c =
            m.beyond(f.realizer[s], f.competitor[s], f.axis[s], int(f.sign[s]));
        failures += c.failure_time(key.time);
        // Scheduled after the segment, so that each event is handled once.
        queue.schedule(h, EventKey{f.next_key + 1 + key.time + u, 1, uint32_t(k), u}, k);
      }
    }
    benchmark::DoNotOptimize(failures);
  }
  state.counters["events"] = double(events);
  state.counters["updates_per_event"] = f.updates_per_event;
}

/// The kinetic tree's real key interval, the second of the shot: the key pass at its start (whose
/// sides the first key verified, as at every later key) and the events up to the next key.
void BM_KineticInterval(benchmark::State& state) {
  Floor& f = floor_setup();
  for (auto _ : state) {
    state.PauseTiming();
    KineticBvh tree(f.meshes, std::nextafter(f.key, 0.0), KineticBvh::Config{});
    tree.advance_to(std::nextafter(f.next_key, 0.0));
    state.ResumeTiming();
    tree.advance_to(std::nextafter(f.after_next_key, 0.0));
    benchmark::DoNotOptimize(tree.stats().events.total());
  }
}

/// The console's report, and each benchmark's milliseconds: the median when repeated.
class FloorReporter : public benchmark::ConsoleReporter {
 public:
  void ReportRuns(const std::vector<Run>& runs) override {
    ConsoleReporter::ReportRuns(runs);
    for (const Run& run : runs) {
      const std::string name = run.run_name.function_name;
      if (run.run_type == Run::RT_Iteration ? !m_ms.contains(name) : run.aggregate_name == "median")
        m_ms[name] = run.GetAdjustedRealTime();
    }
  }
  [[nodiscard]] double ms(const std::string& name) const {
    const auto it = m_ms.find(name);
    return it == m_ms.end() ? 0 : it->second;
  }

 private:
  std::map<std::string, double> m_ms;
};

}  // namespace

BENCHMARK(BM_BottomUpPass)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_FloorKeyComparisons)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_FloorEvents)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_KineticInterval)->Unit(benchmark::kMillisecond);

int main(int argc, char** argv) {
  std::vector<char*> args;
  for (int i = 0; i < argc; ++i) {
    if (std::strncmp(argv[i], "--triangles=", 12) != 0) {
      args.push_back(argv[i]);
      continue;
    }
    // The scene's own limits (a few hundred to 5e7 triangles) are checked when it is made.
    const char* text = argv[i] + 12;
    const char* text_end = text + std::strlen(text);
    const auto [rest, error] = std::from_chars(text, text_end, g_triangles);
    if (error != std::errc() || rest != text_end || g_triangles <= 0) {
      std::fprintf(stderr, "bench_kinetic_tree_floor: --triangles: not a positive integer: '%s'\n",
                   text);
      return 2;
    }
  }
  int count = int(args.size());
  benchmark::Initialize(&count, args.data());
  if (benchmark::ReportUnrecognizedArguments(count, args.data())) return 1;
  try {
    floor_setup();  // the scene and the trees, before any benchmark runs
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_kinetic_tree_floor: %s\n", e.what());
    return 1;
  }
  FloorReporter reporter;
  benchmark::RunSpecifiedBenchmarks(&reporter);
  benchmark::Shutdown();
  const double pass = reporter.ms("BM_BottomUpPass"), keys = reporter.ms("BM_FloorKeyComparisons"),
               events = reporter.ms("BM_FloorEvents"), real = reporter.ms("BM_KineticInterval");
  if (pass <= 0 || keys <= 0 || events <= 0) return 0;  // filtered out
  const Floor& f = floor_setup();
  std::printf(
      "\nwavy-sphere:triangles=%d, one key interval (%llu events, %.2f sides recomputed per "
      "event, %zu certificates):\n",
      g_triangles, static_cast<unsigned long long>(f.events_per_interval), f.updates_per_event,
      f.realizer.size());
  std::printf(
      "  bottom-up pass %.3f ms; floor: keys %.3f ms (%.2f passes) + events %.3f ms "
      "(%.2f passes)",
      pass, keys, keys / pass, events, events / pass);
  if (real > 0)
    std::printf("; the kinetic tree's interval %.3f ms (%.2f passes)", real, real / pass);
  std::printf("\n");
  for (int k : {16, 128}) {
    std::printf("  K = %3d: the floor allows %.1fx the bottom-up update", k,
                k * pass / (keys + events));
    if (real > 0) std::printf(" (the kinetic tree: %.1fx)", k * pass / real);
    std::printf("\n");
  }
  return 0;
}
