#pragma once
// fork() copies only the calling thread: a lock that another thread holds at that instant stays
// held for ever in the child. glibc re-initialises its own locks (malloc, stdio, the loader) in
// the child, but GCC 12's AddressSanitizer runtime does not (libasan has atfork handlers only
// since LLVM 18), and in CI a reading child of model_guard.h, forked while a thread of the old
// pool was working, hung in the sanitizer suite until its 300 s timeout. A fork therefore happens
// under NoThreadBusy, which waits until none of these is at work:
//  - a thread inside a ThreadBusy: every body of util/parallel.h's loops (on whatever thread
//    runs it, the caller's included) and the progress ticker's drawing (renderer/output/progress.cpp);
//  - a thread inside one of the oneTBB arenas of util/parallel.h, counted by an observer on each
//    arena from its entry to its exit (a worker stealing or splitting tasks between bodies runs
//    oneTBB's code, which allocates). While a fork is under way, a thread that enters an arena
//    or a ThreadBusy waits at the door; while one waits, so does a new loop's caller.
// Not covered: oneTBB's worker threads outside kinray's arenas, on their way in or out (oneTBB's
// own spin locks, no allocation) or asleep; and Embree's work, which runs in oneTBB's default
// arena (kinray forks only to read models, before Embree runs). The workers' start-up, which takes
// the runtimes' locks, is over before a loop returns the first time: an arena is warmed up when it
// is created (util/parallel.cpp). Threads that the project starts itself are started with
// start_thread, which returns once the thread runs its own code.
#include <latch>
#include <thread>
#include <utility>

namespace kinray {

/// Held by a thread of the project's own while it works (runs a loop's body, draws a line).
class ThreadBusy {
 public:
  ThreadBusy();
  ~ThreadBusy();
  ThreadBusy(const ThreadBusy&) = delete;
  ThreadBusy& operator=(const ThreadBusy&) = delete;
};

/// Held around fork(): meanwhile no thread of the project's own works and no thread is inside
/// kinray's arenas. Taken on a thread that is itself busy (a model read from inside a parallel
/// body), it cannot wait for the others, which may wait for this one, and then holds nothing.
class NoThreadBusy {
 public:
  NoThreadBusy();
  ~NoThreadBusy();
  NoThreadBusy(const NoThreadBusy&) = delete;
  NoThreadBusy& operator=(const NoThreadBusy&) = delete;

 private:
  bool m_held = false;
};

/// A thread entered (left) one of kinray's oneTBB arenas: called by the arenas' observers
/// (util/parallel.cpp). Entering waits while a NoThreadBusy is held; a thread that starts a
/// loop (`worker` false) and is not busy also waits while a NoThreadBusy waits, so that a fork
/// is not put off for ever by loop after loop.
void thread_enters_arena(bool worker);
void thread_leaves_arena();

/// Threads now busy or inside kinray's arenas (for tests).
[[nodiscard]] int threads_at_work();

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
