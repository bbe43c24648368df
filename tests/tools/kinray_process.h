#pragma once
// Runs the kinray program as a user does, for the tests of its commands: the exit status and
// what it printed on stdout and stderr.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace kinray::test {

struct CommandRun {
  int status = -1;  ///< the exit status, -1 if killed by a signal
  std::string out, err;
};

/// The whole of a file (empty if it cannot be read).
inline std::string read_text(const std::filesystem::path& path) {
  std::ifstream file(path, std::ios::binary);
  std::ostringstream text;
  text << file.rdbuf();
  return text.str();
}

/// Runs `kinray ARGS` with stdin closed; its output is captured through two files in `folder`
/// (which must exist), removed afterwards. `launcher`, when given, runs the program (e.g. as
/// another user).
inline CommandRun run_kinray(const std::string& args, const std::filesystem::path& folder,
                             const std::string& launcher = "") {
  const std::filesystem::path out = folder / "stdout.txt", err = folder / "stderr.txt";
  const std::string command = launcher + " '" + KINRAY_BINARY + "' " + args + " </dev/null >'" +
                              out.string() + "' 2>'" + err.string() + "'";
  const int raw = std::system(command.c_str());
  CommandRun run;
  run.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  run.out = read_text(out);
  run.err = read_text(err);
  std::filesystem::remove(out);
  std::filesystem::remove(err);
  return run;
}

/// A test of the program with an empty folder of its own, named after the test and the process
/// (several checkouts may run the suite on one machine at once).
class CommandTest : public ::testing::Test {
 protected:
  void SetUp() override {
    m_dir =
        std::filesystem::temp_directory_path() /
        ("kinray_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) +
         "_" + std::to_string(::getpid()));
    std::filesystem::remove_all(m_dir);
    std::filesystem::create_directories(m_dir);
  }
  void TearDown() override { std::filesystem::remove_all(m_dir); }
  /// Runs `kinray ARGS` with stdin closed and stdout/stderr captured.
  [[nodiscard]] CommandRun kinray(const std::string& args) const { return run_kinray(args, m_dir); }
  /// `name` in the test's folder.
  [[nodiscard]] std::string path(const std::string& name) const { return (m_dir / name).string(); }

  std::filesystem::path m_dir;
};

}  // namespace kinray::test
