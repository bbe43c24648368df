#include "util/thread_pool.h"

#include <atomic>
#include <exception>

#include "util/fork_gate.h"

namespace kinray {

namespace {

/// Set while this thread runs a task: a nested run must not wait on the pool it is part of (and
/// the caller must not try_lock the submit mutex it already holds).
thread_local bool t_in_task = false;

}  // namespace

struct ThreadPool::Run {
  size_t tasks = 0;
  size_t helpers = 0;  ///< workers wanted
  Task task = nullptr;
  void* context = nullptr;
  size_t joined = 0;  ///< workers that entered, guarded by m_mutex
  std::atomic<size_t> next{0};
  std::mutex error_mutex;
  std::exception_ptr error;
};

ThreadPool::~ThreadPool() {
  {
    std::lock_guard lock(m_mutex);
    m_stop = true;
  }
  m_wake.notify_all();
  for (std::thread& worker : m_workers) worker.join();
}

ThreadPool& ThreadPool::shared() {
  static ThreadPool pool;
  return pool;
}

size_t ThreadPool::worker_count() const {
  std::lock_guard lock(m_mutex);
  return m_workers.size();
}

void ThreadPool::execute(Run& run) {
  const ThreadBusy busy;
  const bool outer = t_in_task;
  t_in_task = true;
  for (size_t k = run.next.fetch_add(1, std::memory_order_relaxed); k < run.tasks;
       k = run.next.fetch_add(1, std::memory_order_relaxed)) {
    try {
      run.task(run.context, k);
    } catch (...) {
      std::lock_guard lock(run.error_mutex);
      if (!run.error) run.error = std::current_exception();
      run.next.store(run.tasks, std::memory_order_relaxed);
    }
  }
  t_in_task = outer;
}

bool ThreadPool::try_run(size_t tasks, size_t helpers, Task task, void* context) {
  if (t_in_task) return false;
  std::unique_lock submit(m_submit, std::try_to_lock);
  if (!submit.owns_lock()) return false;
  Run run;
  run.tasks = tasks;
  run.helpers = helpers;
  run.task = task;
  run.context = context;
  {
    std::lock_guard lock(m_mutex);
    // A worker that cannot be started (std::system_error) leaves the pool as it was.
    while (m_workers.size() < helpers) m_workers.push_back(start_thread([this] { work(); }));
    m_run = &run;
    ++m_generation;
  }
  m_wake.notify_all();
  execute(run);
  {
    std::unique_lock lock(m_mutex);
    m_run = nullptr;  // late workers no longer join
    m_idle.wait(lock, [&] { return m_active == 0; });
  }
  if (run.error) std::rethrow_exception(run.error);
  return true;
}

void ThreadPool::work() {
  uint64_t seen = 0;
  std::unique_lock lock(m_mutex);
  for (;;) {
    m_wake.wait(lock, [&] {
      return m_stop || (m_run != nullptr && m_generation != seen && m_run->joined < m_run->helpers);
    });
    if (m_stop) return;
    seen = m_generation;
    Run& run = *m_run;
    ++run.joined;
    ++m_active;
    lock.unlock();
    execute(run);
    lock.lock();
    if (--m_active == 0) m_idle.notify_all();
  }
}

}  // namespace kinray
