#pragma once
// A small persistent pool of worker threads behind parallel_chunks (util/parallel.h): the
// per-frame loops (read-out, event bands, shading, Embree's rows) would otherwise start and join
// threads at every call, tens of microseconds per frame. The tasks of a run are claimed one at a
// time by the caller and the helpers, so a helper that wakes late (the machine is shared) costs
// nothing: the caller claims what is left and waits only for helpers that started a task.
#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <mutex>
#include <thread>
#include <vector>

namespace kinray {

class ThreadPool {
 public:
  /// A task of a run: task(context, k) for k in [0, tasks).
  using Task = void (*)(void* context, size_t k);

  ThreadPool() = default;
  /// Stops and joins the workers (they are idle: a run returns only when its tasks are done).
  ~ThreadPool();
  ThreadPool(const ThreadPool&) = delete;
  ThreadPool& operator=(const ThreadPool&) = delete;

  /// The process's pool, created on first use and joined at exit.
  [[nodiscard]] static ThreadPool& shared();

  /// Runs task(context, k) for every k in [0, tasks) on the calling thread and up to `helpers`
  /// workers, each claiming the next unclaimed k; returns when every claimed task has returned.
  /// The first exception a task throws is rethrown here (the tasks not yet claimed are skipped).
  /// Returns false without running anything when the pool is taken (by another thread, or this
  /// call comes from inside a task): the caller then uses threads of its own.
  bool try_run(size_t tasks, size_t helpers, Task task, void* context);

  /// Workers started so far (they are kept for later runs).
  [[nodiscard]] size_t worker_count() const;

 private:
  struct Run;
  void work();
  static void execute(Run& run);

  std::mutex m_submit;             ///< held by the caller for a whole run
  mutable std::mutex m_mutex;      ///< guards everything below
  std::condition_variable m_wake;  ///< a run was posted, or stop
  std::condition_variable m_idle;  ///< the last helper of a run left it
  std::vector<std::thread> m_workers;
  Run* m_run = nullptr;  ///< the open run; null once its caller has finished its share
  uint64_t m_generation = 0;
  size_t m_active = 0;  ///< workers inside the current run
  bool m_stop = false;
};

}  // namespace kinray
