#include "scenes/model_guard.h"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iostream>

#include "util/fork_gate.h"

namespace kinray {

size_t reader_address_space() {
  size_t used_pages = 0;
  std::ifstream("/proc/self/statm") >> used_pages;  // first field: total program size in pages
  const long page = sysconf(_SC_PAGESIZE), physical = sysconf(_SC_PHYS_PAGES);
  if (page <= 0 || physical <= 0) return 0;
  const size_t budget = std::min(size_t(physical) / 2 * size_t(page), size_t(8) << 30);
  return used_pages * size_t(page) + budget;
}

namespace {

/// The child's side of run_in_child: runs `work` under the address-space limit and writes its
/// failure message, if any, to `out`; never returns.
[[noreturn]] void run_child(int out, const std::function<std::string()>& work,
                            size_t address_space_bytes) {
  dup2(STDERR_FILENO, STDOUT_FILENO);
  // The child's crash is the parent's verdict: it must die by the signal. A handler inherited
  // from the parent (AddressSanitizer's, libFuzzer's in the sanitizer and fuzz builds) would
  // report it as its own finding and exit with a status instead.
  for (const int crash : {SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT}) std::signal(crash, SIG_DFL);
  if (address_space_bytes > 0) {
    const rlimit limit{rlim_t(address_space_bytes), rlim_t(address_space_bytes)};
    setrlimit(RLIMIT_AS, &limit);
  }
  std::string message;
  try {
    message = work();
  } catch (const std::exception& error) {
    message = error.what();
    if (message.empty()) message = "failed";
  } catch (...) {
    message = "failed with an unknown exception";
  }
  for (size_t done = 0; done < message.size();) {
    const ssize_t n = write(out, message.data() + done, message.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;
    done += size_t(n);
  }
  _exit(message.empty() ? 0 : 1);  // no atexit handlers or stdio flushes of the parent's state
}

/// Reads the child's message from `in` until it closes the pipe or the timeout passes; true when
/// the timeout passed.
bool read_child_message(int in, double timeout_seconds, std::string& message) {
  const auto deadline =
      std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_seconds);
  for (;;) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
        deadline - std::chrono::steady_clock::now());
    if (left.count() <= 0) return true;
    pollfd request{in, POLLIN, 0};
    const int ready = poll(&request, 1, int(std::min<long long>(left.count(), 1000)));
    if (ready < 0 && errno != EINTR) return false;
    if (ready <= 0) continue;
    char buffer[4096];
    const ssize_t n = read(in, buffer, sizeof buffer);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;  // end of file: the child has exited (or crashed)
    message.append(buffer, size_t(n));
  }
}

}  // namespace

std::optional<std::string> run_in_child(const std::function<std::string()>& work,
                                        double timeout_seconds, size_t address_space_bytes) {
  int fds[2];
  if (pipe2(fds, O_CLOEXEC) != 0) return std::nullopt;
  // Pending output would otherwise be copied into the child and written twice.
  std::cout.flush();
  std::cerr.flush();
  std::fflush(nullptr);
  // Meanwhile no other thread of ours holds a lock the child may need. Only the parent lets go
  // of the gate: the child leaves by _exit, and there the gate's recorded owner is not itself.
  std::optional<NoThreadBusy> quiet(std::in_place);
  const pid_t child = fork();
  if (child != 0) quiet.reset();
  if (child < 0) {
    close(fds[0]);
    close(fds[1]);
    return std::nullopt;
  }
  if (child == 0) {
    close(fds[0]);
    run_child(fds[1], work, address_space_bytes);
  }
  close(fds[1]);
  std::string message;
  const bool timed_out = read_child_message(fds[0], timeout_seconds, message);
  close(fds[0]);
  if (timed_out) kill(child, SIGKILL);
  int status = 0;
  while (waitpid(child, &status, 0) < 0 && errno == EINTR) {
  }
  if (timed_out)
    return "did not finish within " + std::to_string(int(timeout_seconds)) +
           " s (a hang on malformed input?)";
  if (WIFSIGNALED(status)) {
    const int signal = WTERMSIG(status);
    const char* name = strsignal(signal);
    return "crashed the reader with signal " + std::to_string(signal) + " (" +
           (name ? name : "unknown") + "): malformed input";
  }
  if (WIFEXITED(status) && WEXITSTATUS(status) == 0) return std::nullopt;
  return message.empty() ? std::string("failed") : message;
}

StdoutToStderr::StdoutToStderr() {
  std::cout.flush();
  std::fflush(stdout);
  m_saved = dup(STDOUT_FILENO);
  if (m_saved >= 0) dup2(STDERR_FILENO, STDOUT_FILENO);
}

StdoutToStderr::~StdoutToStderr() {
  std::cout.flush();
  std::fflush(stdout);
  if (m_saved >= 0) {
    dup2(m_saved, STDOUT_FILENO);
    close(m_saved);
  }
}

}  // namespace kinray
