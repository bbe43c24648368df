#pragma once
// Runs the kinray program with its stderr on a pseudo-terminal, as a user at a terminal sees it:
// what kinray draws only when stderr is a terminal (the progress bar, the loading notes).
#include <fcntl.h>
#include <poll.h>
#include <pty.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <csignal>
#include <filesystem>
#include <string>

#include "tests/tools/kinray_process.h"

namespace kinray::test {

/// Runs `kinray ARGS` with stdin closed, stdout captured through a file in `folder` and stderr
/// on a pseudo-terminal whose bytes are returned as `err`; killed after `timeout_s` seconds.
inline CommandRun run_kinray_on_terminal(const std::string& args,
                                         const std::filesystem::path& folder, int timeout_s = 120) {
  const std::filesystem::path out = folder / "stdout.txt";
  int terminal = -1, child_side = -1;
  CommandRun run;
  if (::openpty(&terminal, &child_side, nullptr, nullptr, nullptr) != 0) return run;
  const std::string command =
      std::string("exec '") + KINRAY_BINARY + "' " + args + " </dev/null >'" + out.string() + "'";
  const pid_t pid = ::fork();
  if (pid == 0) {
    ::close(terminal);
    ::dup2(child_side, STDERR_FILENO);
    ::close(child_side);
    ::execl("/bin/sh", "sh", "-c", command.c_str(), static_cast<char*>(nullptr));
    ::_exit(127);
  }
  ::close(child_side);
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(timeout_s);
  char buffer[4096];
  // Read until the child's side is closed (EIO on Linux), so the terminal never fills up.
  for (;;) {
    pollfd ready{terminal, POLLIN, 0};
    if (std::chrono::steady_clock::now() > deadline) {
      ::kill(pid, SIGKILL);
      break;
    }
    if (::poll(&ready, 1, 200) <= 0) continue;
    const ssize_t n = ::read(terminal, buffer, sizeof buffer);
    if (n > 0)
      run.err.append(buffer, size_t(n));
    else if (n == 0 || errno != EINTR)
      break;
  }
  ::close(terminal);
  int raw = 0;
  ::waitpid(pid, &raw, 0);
  run.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  run.out = read_text(out);
  std::filesystem::remove(out);
  return run;
}

}  // namespace kinray::test
