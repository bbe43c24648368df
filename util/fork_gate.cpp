#include "util/fork_gate.h"

#include <shared_mutex>

namespace kinray {

namespace {

std::shared_mutex& gate() {
  static std::shared_mutex mutex;
  return mutex;
}

/// Busy levels of this thread (a pool task may start a parallel loop of its own threads).
thread_local int t_busy = 0;

}  // namespace

ThreadBusy::ThreadBusy() {
  if (t_busy++ == 0) gate().lock_shared();
}

ThreadBusy::~ThreadBusy() {
  if (--t_busy == 0) gate().unlock_shared();
}

NoThreadBusy::NoThreadBusy() {
  if (t_busy > 0) return;
  gate().lock();
  m_held = true;
}

NoThreadBusy::~NoThreadBusy() {
  if (m_held) gate().unlock();
}

}  // namespace kinray
