#include "util/fork_gate.h"

#include <atomic>
#include <condition_variable>
#include <mutex>

namespace kinray {

namespace {

// The working threads are counted in `g_at_work` without a lock (a loop's body enters and leaves
// at every range); a fork sets `g_forking` once the count is zero and checks it again. Both sides
// write first and read second, sequentially consistent: either the fork sees the count or the
// entering thread sees the fork (it then steps back and waits for the fork to end).
std::atomic<int> g_at_work{0};
std::atomic<bool> g_forking{false};
std::atomic<int> g_fork_waiters{0};  ///< NoThreadBusy waiting for the count to reach zero
std::mutex g_mutex;                  ///< guards the waits on g_changed
std::condition_variable g_changed;   ///< the count reached zero, or a fork ended

/// Busy levels of this thread (a loop's body may run a loop of its own).
thread_local int t_busy = 0;

void leave() {
  if (g_at_work.fetch_sub(1) == 1 && g_fork_waiters.load() > 0) {
    const std::lock_guard lock(g_mutex);
    g_changed.notify_all();
  }
}

void enter() {
  for (;;) {
    g_at_work.fetch_add(1);
    if (!g_forking.load()) return;
    leave();
    std::unique_lock lock(g_mutex);
    g_changed.wait(lock, [] { return !g_forking.load(); });
  }
}

}  // namespace

ThreadBusy::ThreadBusy() {
  if (t_busy++ == 0) enter();
}

ThreadBusy::~ThreadBusy() {
  if (--t_busy == 0) leave();
}

void thread_enters_arena(bool worker) {
  if (!worker && t_busy == 0 && g_fork_waiters.load() > 0) {
    std::unique_lock lock(g_mutex);
    g_changed.wait(lock, [] { return g_fork_waiters.load() == 0; });
  }
  enter();
}

void thread_leaves_arena() {
  leave();
}

int threads_at_work() {
  return g_at_work.load();
}

NoThreadBusy::NoThreadBusy() {
  if (t_busy > 0) return;
  std::unique_lock lock(g_mutex);
  g_fork_waiters.fetch_add(1);
  for (;;) {
    g_changed.wait(lock, [] { return !g_forking.load() && g_at_work.load() == 0; });
    g_forking.store(true);
    if (g_at_work.load() == 0) break;
    // A thread entered meanwhile: it goes on (it saw no fork, or steps back and waits below).
    g_forking.store(false);
    g_changed.notify_all();
  }
  g_fork_waiters.fetch_sub(1);
  g_changed.notify_all();  // the loops held back at their arena's door (they wait for the fork)
  m_held = true;
}

NoThreadBusy::~NoThreadBusy() {
  if (!m_held) return;
  const std::lock_guard lock(g_mutex);
  g_forking.store(false);
  g_changed.notify_all();
}

}  // namespace kinray
