#include "util/parallel.h"

#include <oneapi/tbb/global_control.h>
#include <oneapi/tbb/task_scheduler_observer.h>

#include <atomic>
#include <cfenv>
#include <chrono>
#include <map>
#include <memory>
#include <mutex>
#include <thread>

namespace kinray {

int resolve_threads(int requested) {
  if (requested > 0) return requested;
  const unsigned n = std::thread::hardware_concurrency();
  return n == 0 ? 1 : int(n);
}

namespace parallel_detail {

namespace {

/// Counts the threads inside an arena for the fork gate (util/fork_gate.h), from their entry to
/// their exit, and the workers that ever entered (for the warm-up).
class ArenaWatch : public tbb::task_scheduler_observer {
 public:
  explicit ArenaWatch(tbb::task_arena& arena) : tbb::task_scheduler_observer(arena) {}
  void on_scheduler_entry(bool is_worker) override {
    thread_enters_arena(is_worker);
    if (is_worker) m_workers_entered.fetch_add(1, std::memory_order_relaxed);
  }
  void on_scheduler_exit(bool) override { thread_leaves_arena(); }
  [[nodiscard]] int workers_entered() const {
    return m_workers_entered.load(std::memory_order_relaxed);
  }

 private:
  std::atomic<int> m_workers_entered{0};
};

struct Arena {
  explicit Arena(int threads) : arena(threads), watch(arena) {
    // oneTBB runs an arena's tasks in the floating-point environment of the thread that created
    // it, the caller's own share included: the default one, whoever creates it (a body that wants
    // denormals flushed sets that itself, renderer/flush_denormals.h).
    std::fenv_t caller;
    std::fegetenv(&caller);
    std::fesetenv(FE_DFL_ENV);
    arena.initialize();
    std::fesetenv(&caller);
    watch.observe(true);
  }
  tbb::task_arena arena;
  ArenaWatch watch;
};

/// Runs a loop of one item per thread that waits (up to a limit: other arenas, Embree's, may hold
/// the workers) until as many workers as the arena can have have entered it: from then on their
/// start-up (thread creation, which takes the runtimes' locks) is over, and a fork cannot catch it.
void warm_up(Arena& entry, int threads) {
  const int workers = threads - 1;
  if (workers <= 0) return;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::milliseconds(500);
  entry.arena.execute([&] {
    tbb::parallel_for(
        tbb::blocked_range<int>(0, threads, 1),
        [&](const tbb::blocked_range<int>&) {
          while (entry.watch.workers_entered() < workers &&
                 std::chrono::steady_clock::now() < deadline)
            std::this_thread::yield();
        },
        tbb::simple_partitioner());
  });
}

}  // namespace

tbb::task_arena& arena(int requested) {
  // No more threads than oneTBB can run at once (the cores, unless a global_control says
  // otherwise): a larger arena would get no more workers, and oneTBB warns on stderr.
  const int threads = std::min(
      requested,
      int(tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism)));
  // Never destroyed: a loop may still run on another thread while the process exits.
  static std::mutex& mutex = *new std::mutex;
  static std::map<int, Arena*>& arenas = *new std::map<int, Arena*>;
  const std::lock_guard lock(mutex);
  Arena*& entry = arenas[threads];
  if (entry == nullptr) {
    entry = new Arena(threads);
    warm_up(*entry, threads);
  }
  return entry->arena;
}

}  // namespace parallel_detail

}  // namespace kinray
