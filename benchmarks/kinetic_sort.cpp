// Kinetic sorting benchmark: n points with random linear motions, positions uniform in [0, n)
// (density 1) and velocities uniform in [-1, 1]; ids numbered by initial position, inserted in a
// random order. Two workloads:
//  - window: the time span [0, 4]. The sorted list's swaps are local: about 1.3 n events.
//  - full:   the time span [0, 1e9], i.e. every event (the last crossings happen long before):
//            the front-only structures' whole history (the lower envelope of the lines, a
//            tournament's O(n log n) events); the sorted list only for small n (n^2/4 swaps).
// Reports events, events per second of event processing (construction excluded; thread CPU
// time, reported as the benchmark's manual time), certificate work per event and bytes per
// object (structure + queue); validates the final front (and the whole order for the sorted
// list) against a brute-force sort at the end of every run; prints at exit the fitted growth
// exponent of the event count and its ratio to n log2 n.
//
//   build/bin/bench_kinetic_sort [--benchmark_filter=Tournament]

#include <benchmark/benchmark.h>

#include <algorithm>
#include <ctime>
#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "kinetic/core/root_finding.h"
#include "kinetic/core/simulator.h"
#include "kinetic/sort/kinetic_heap.h"
#include "kinetic/sort/kinetic_sort.h"
#include "kinetic/sort/kinetic_sorted_list.h"
#include "kinetic/sort/linear_motion_keys.h"
#include "kinetic/sort/kinetic_tournament.h"

namespace {

using namespace kinray;

constexpr double kWindow = 4.0;
constexpr double kFull = 1e9;

// CPU time of this thread: the event processing is timed on one core, unaffected by other
// processes sharing the machine.
double thread_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

struct Scenario {
  LinearMotionKeys keys;
  std::vector<uint32_t> ids;
};

const Scenario& scenario(size_t n) {
  static std::map<size_t, std::unique_ptr<Scenario>> cache;
  auto& slot = cache[n];
  if (!slot) {
    slot = std::make_unique<Scenario>();
    std::mt19937_64 rng(20240 + n);
    std::uniform_real_distribution<double> position(0, static_cast<double>(n)), velocity(-1, 1);
    // Ids are numbered by initial position (memory order = initial order, as a renderer would
    // lay out its objects); they are inserted in a random order.
    std::vector<double> x(n);
    for (double& xi : x) xi = position(rng);
    std::sort(x.begin(), x.end());
    for (size_t i = 0; i < n; ++i) slot->ids.push_back(slot->keys.add(x[i], velocity(rng)));
    std::shuffle(slot->ids.begin(), slot->ids.end(), rng);
  }
  return *slot;
}

struct Record {
  size_t n = 0;
  double events = 0, rate = 0;
};
std::map<std::string, std::vector<Record>>& records() {
  static std::map<std::string, std::vector<Record>> r;
  return r;
}

template <class S>
bool validate(const S& s, const LinearMotionKeys& keys, size_t n, double t) {
  double lowest = std::numeric_limits<double>::infinity();
  for (uint32_t id = 0; id < n; ++id) lowest = std::min(lowest, keys.value(id, t));
  const auto front = s.front();
  if (!front || keys.value(*front, t) > lowest + 1e-9 * (1 + std::fabs(lowest))) return false;
  if constexpr (std::is_same_v<S, KineticSortedList<LinearMotionKeys>>) {
    bool sorted = true;
    double previous = -std::numeric_limits<double>::infinity();
    size_t count = 0;
    s.for_each_in_order([&](uint32_t id) {
      const double v = keys.value(id, t);
      sorted &= v >= previous - 1e-9 * (1 + std::fabs(v));
      previous = v;
      ++count;
    });
    return sorted && count == n;
  }
  return true;
}

template <class S>
void BM_KineticSort(benchmark::State& state, std::string name, size_t n, double span) {
  const Scenario& sc = scenario(n);
  double events = 0, renewals = 0, seconds = 0, work = 0, bytes = 0, queue_bytes = 0;
  int64_t runs = 0;
  for (auto _ : state) {
    Simulator sim;
    sim.queue().reserve(n);
    S s(sc.keys, sim.queue(), 0);
    s.insert_all(sc.ids, 0);
    const double work_built = static_cast<double>(s.stats().work);
    const double start = thread_seconds();
    sim.advance_to(span, [&](const EventKey&, uint64_t payload) {
      s.handle_event(payload, sim.now());
    });
    const double elapsed = thread_seconds() - start;
    state.SetIterationTime(elapsed);
    if (!validate(s, sc.keys, n, span)) {
      state.SkipWithError("front / order differs from the brute-force sort");
      break;
    }
    const KineticSortStats& st = s.stats();
    events += static_cast<double>(st.events());
    renewals += static_cast<double>(st.events_renewal);
    work += static_cast<double>(st.work) - work_built;
    bytes = static_cast<double>(s.memory_bytes());
    queue_bytes = static_cast<double>(sim.queue().memory_bytes());
    seconds += elapsed;
    ++runs;
  }
  if (runs == 0) return;
  const double per_run = events / static_cast<double>(runs);
  state.counters["events"] = per_run;
  state.counters["events_per_s"] = seconds > 0 ? events / seconds : 0;
  state.counters["work_per_event"] = events > 0 ? work / (events + renewals) : 0;
  state.counters["bytes_per_object"] = (bytes + queue_bytes) / static_cast<double>(n);
  auto& rec = records()[name];
  rec.erase(std::remove_if(rec.begin(), rec.end(), [&](const Record& r) { return r.n == n; }),
            rec.end());
  rec.push_back({n, per_run, seconds > 0 ? events / seconds : 0});
}

template <class S>
void add(const std::string& structure, const std::string& workload, double span,
         const std::vector<size_t>& sizes) {
  for (size_t n : sizes) {
    const std::string family = structure + "/" + workload;
    auto* b = benchmark::RegisterBenchmark(
        (family + "/" + std::to_string(n)).c_str(),
        [family, n, span](benchmark::State& state) { BM_KineticSort<S>(state, family, n, span); });
    // A fixed number of runs (each with an untimed construction): about 1e5 objects in total.
    b->Iterations(static_cast<int64_t>(std::max<size_t>(1, 100000 / n)));
    b->UseManualTime()->Unit(benchmark::kMillisecond);
  }
}

// first_failure on degree-5 certificates (the per-pixel depth order's degree) over [0, 1]:
// random products of five real or complex factors, split by whether a failure exists.
void BM_FirstFailureDegree5(benchmark::State& state) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<Polynomial> with_root, without_root;
  while (with_root.size() < 4096 || without_root.size() < 4096) {
    Polynomial p(1.0);
    for (int k = 0; k < 5; ++k) p = p * Polynomial{u(rng) * 4, 1};  // roots in [-4, 4]
    if (sign_after(p, 0) < 0) p = -p;
    (first_failure(p, 0, 1) ? with_root : without_root).push_back(p);
  }
  const auto& set = state.range(0) ? with_root : without_root;
  root_stats() = {};
  size_t i = 0, found = 0;
  for (auto _ : state) {
    found += first_failure(set[i++ & 4095], 0, 1).has_value();
  }
  benchmark::DoNotOptimize(found);
  const RootStats& st = root_stats();
  state.counters["fast_path_share"] =
      st.calls ? static_cast<double>(st.fast_path_no_root) / static_cast<double>(st.calls) : 0;
  state.counters["subdivisions_per_call"] =
      st.calls ? static_cast<double>(st.subdivisions) / static_cast<double>(st.calls) : 0;
  state.counters["refinements_per_call"] =
      st.calls ? static_cast<double>(st.refinements) / static_cast<double>(st.calls) : 0;
  state.SetLabel(state.range(0) ? "with a failure in [0,1]" : "no failure in [0,1]");
}

void register_all() {
  benchmark::RegisterBenchmark("FirstFailure/degree5", BM_FirstFailureDegree5)->Arg(0)->Arg(1);
  const std::vector<size_t> all{100, 1000, 10000, 100000, 1000000};
  add<KineticSortedList<LinearMotionKeys>>("SortedList", "window", kWindow, all);
  add<KineticTournament<LinearMotionKeys>>("Tournament", "full", kFull, all);
  add<KineticHeap<LinearMotionKeys>>("Heap", "full", kFull, all);
  add<KineticSortedList<LinearMotionKeys>>("SortedList", "full", kFull, {100, 1000, 3000});
}

// Least-squares fit of log(events) = a + k log(n), and events / (n log2 n) per size.
void print_summary() {
  if (records().empty()) return;
  std::printf("\nEvent count growth (positions U[0,n), velocities U[-1,1]; window [0, %g], full "
              "[0, %g]):\n", kWindow, kFull);
  for (auto& [name, recs] : records()) {
    std::sort(recs.begin(), recs.end(), [](const Record& a, const Record& b) { return a.n < b.n; });
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    int m = 0;
    for (const Record& r : recs) {
      if (r.events <= 0) continue;
      const double x = std::log(static_cast<double>(r.n)), y = std::log(r.events);
      sx += x, sy += y, sxx += x * x, sxy += x * y, ++m;
    }
    const double k = m > 1 ? (m * sxy - sx * sy) / (m * sxx - sx * sx) : 0;
    std::printf("  %-18s fitted exponent events ~ n^%.3f;", name.c_str(), k);
    std::printf("  events / (n log2 n):");
    for (const Record& r : recs)
      std::printf(" n=%zu: %.4f", r.n,
                  r.events / (static_cast<double>(r.n) * std::log2(static_cast<double>(r.n))));
    std::printf("\n  %-18s events/s:", "");
    for (const Record& r : recs) std::printf(" n=%zu: %.3gM", r.n, r.rate * 1e-6);
    std::printf("\n");
  }
}

}  // namespace

int main(int argc, char** argv) {
  register_all();
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  print_summary();
  return 0;
}
