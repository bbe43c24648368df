#pragma once
// fork() copies only the calling thread: a lock that another thread holds at that instant stays
// held for ever in the child. glibc re-initialises its own locks (malloc, stdio, the loader) in
// the child, but GCC 12's AddressSanitizer runtime does not (libasan has atfork handlers only
// since LLVM 18), and in CI a reading child of model_guard.h, forked while a thread of the pool
// existed, hung in the sanitizer suite until its 300 s timeout. So the threads the project starts
// are started with start_thread (which returns once the thread runs its own code: thread start-up
// takes the runtimes' locks) and hold a ThreadBusy while they work, never while they wait; a
// fork happens under NoThreadBusy, which waits until none of them is working. Threads of other
// libraries (oneTBB's, under Embree) are not covered; kinray forks only to read models, before
// Embree runs.
#include <latch>
#include <thread>
#include <utility>

namespace kinray {

/// Held by a thread of the project's own while it works (runs tasks, draws a line).
class ThreadBusy {
 public:
  ThreadBusy();
  ~ThreadBusy();
  ThreadBusy(const ThreadBusy&) = delete;
  ThreadBusy& operator=(const ThreadBusy&) = delete;
};

/// Held around fork(): meanwhile no thread of the project's own works. Taken on a thread that is
/// itself busy (a model read from inside a parallel task), it cannot wait for the others, which
/// may wait for this one, and then holds nothing.
class NoThreadBusy {
 public:
  NoThreadBusy();
  ~NoThreadBusy();
  NoThreadBusy(const NoThreadBusy&) = delete;
  NoThreadBusy& operator=(const NoThreadBusy&) = delete;

 private:
  bool m_held = false;
};

/// Starts a thread running f() and returns once f has begun: the thread's start-up in libc and in
/// the sanitizers' runtimes is over, so a fork from now on cannot catch it half-way.
template <class F>
std::thread start_thread(F&& f) {
  std::latch started(1);
  std::thread thread([&started, f = std::forward<F>(f)]() mutable {
    started.count_down();  // the last use of `started`: the caller may return at once
    f();
  });
  started.wait();
  return thread;
}

}  // namespace kinray
