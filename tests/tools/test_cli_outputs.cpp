// Output is never destroyed by a command that then fails: every output path is checked before
// anything is loaded, rendered or written; empty paths are refused; a shorter re-render leaves no
// frames of the longer one; Ctrl-C during a video render leaves no hidden temporary file; and a
// write that fails once the work started (disk full) is exit status 1, bad input 2.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

#include "tests/tools/kinray_process.h"

namespace kinray {
namespace {

namespace fs = std::filesystem;

constexpr const char* kTiny = "wavy-sphere:triangles=600";

class CliOutputs : public ::testing::Test {
 protected:
  void SetUp() override {
    m_dir = fs::temp_directory_path() /
            ("kinray_outputs_" +
             std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(m_dir);
    fs::create_directories(m_dir / "base");
    std::ofstream(m_dir / "base" / "frame_00000.png") << "an earlier frame";
  }
  void TearDown() override {
    fs::permissions(m_dir, fs::perms::owner_all, fs::perm_options::add);
    fs::remove_all(m_dir);
  }
  [[nodiscard]] test::CommandRun kinray(const std::string& args) const {
    return test::run_kinray(args, m_dir);
  }
  /// The quoted path of `name` in the test's folder. Appended piece by piece: GCC 12 warns
  /// (-Wrestrict, a false positive) on "'" + std::string.
  [[nodiscard]] std::string path(const std::string& name) const {
    std::string quoted(1, '\'');
    return quoted.append((m_dir / name).string()).append(1, '\'');
  }
  [[nodiscard]] std::vector<std::string> names(const std::string& folder) const {
    std::vector<std::string> result;
    for (const auto& entry : fs::directory_iterator(m_dir / folder))
      result.push_back(entry.path().filename().string());
    std::sort(result.begin(), result.end());
    return result;
  }
  /// Status 2, one line naming `flag`, and base/ exactly as it was.
  void expect_refused(const test::CommandRun& run, const std::string& flag) const {
    EXPECT_EQ(run.status, 2) << run.err;
    EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << run.err;
    EXPECT_EQ(run.err.rfind("kinray: error: " + flag + ":", 0), 0u) << run.err;
    EXPECT_EQ(names("base"), std::vector<std::string>{"frame_00000.png"});
    EXPECT_EQ(test::read_text(m_dir / "base" / "frame_00000.png"), "an earlier frame");
  }

  fs::path m_dir;
};

TEST_F(CliOutputs, UnwritableOutputsAreRefusedBeforeAnythingIsWritten) {
  // /proc takes no new files, even from root; a file where a folder must be fails for anyone.
  std::ofstream(m_dir / "a-file") << "x";
  const std::string render =
      std::string("render ") + kTiny + " --size 16x16 --frames 2 --out " + path("base") + " ";
  const std::string diff = std::string("diff ") + kTiny + " --size 16x16 --frames 2 ";
  const std::string bench = std::string("bench ") + kTiny +
                            " --size 16x16 --inbetweens 1 --reference-frames 1 "
                            "--repetitions 1 --embree-modes refit/1 ";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {render + "--stats /proc/kinray-test/s.json", "--stats"},
      {render + "--stats /proc/s.json", "--stats"},
      {render + "--video /proc/v.mp4", "--video"},
      {render + "--stats " + path("a-file/s.json"), "--stats"},
      {render + "--stats " + path("base"), "--stats"},
      {std::string("render ") + kTiny + " --out " + path("base/frame_00000.png"), "--out"},
      {std::string("render ") + kTiny + " --out /proc/kinray-test", "--out"},
      {diff + "--json /proc/d.json", "--json"},
      {diff + "--report " + path("a-file"), "--report"},
      {bench + "--json /proc/b.json", "--json"},
      {bench + "--csv " + path("base"), "--csv"},
      {bench + "--charts " + path("a-file"), "--charts"},
      {"regress --case wavy-sphere --references '" + std::string(KINRAY_SOURCE_DIR) +
           "/images/regression' --report /proc/r",
       "--report"},
  };
  for (const auto& [args, flag] : cases) {
    SCOPED_TRACE(args);
    expect_refused(kinray(args), flag);
  }
  // A folder without write permission: root writes into it anyway, so under root (as CI runs)
  // the program runs as the unprivileged user 'nobody' (setpriv, util-linux), with the test's own
  // folders open to it.
  std::string launcher;
  if (::geteuid() == 0) {
    if (std::system("command -v setpriv >/dev/null 2>&1") != 0)
      GTEST_SKIP() << "running as root without setpriv: no user for whom a folder is read-only";
    launcher = "setpriv --reuid=65534 --regid=65534 --clear-groups";
    for (const fs::path& open : {m_dir, m_dir / "base"}) fs::permissions(open, fs::perms::all);
  }
  fs::create_directories(m_dir / "read-only");
  fs::permissions(m_dir / "read-only", fs::perms::owner_read | fs::perms::owner_exec |
                                           fs::perms::others_read | fs::perms::others_exec);
  expect_refused(test::run_kinray(render + "--stats " + path("read-only/s.json"), m_dir, launcher),
                 "--stats");
  expect_refused(test::run_kinray(std::string("render ") + kTiny + " --out " + path("read-only/f"),
                                  m_dir, launcher),
                 "--out");
}

TEST_F(CliOutputs, EmptyPathsAreRefused) {
  for (const auto& [args, flag] : std::vector<std::pair<std::string, std::string>>{
           {std::string("render ") + kTiny + " --out ''", "--out"},
           {std::string("render ") + kTiny + " --out " + path("base") + " --stats ''", "--stats"},
           {std::string("render ") + kTiny + " --out " + path("base") + " --video ''", "--video"},
           {std::string("diff ") + kTiny + " --json ''", "--json"},
           {std::string("bench ") + kTiny + " --charts ''", "--charts"},
       }) {
    SCOPED_TRACE(args);
    expect_refused(kinray(args), flag);
  }
  EXPECT_FALSE(fs::exists("out/wavy-sphere-should-not-exist"));
}

TEST_F(CliOutputs, AShorterRerenderRemovesTheLongerRendersFrames) {
  const std::string render =
      std::string("render ") + kTiny + " --backend embree --size 16x16 --out " + path("f");
  ASSERT_EQ(kinray(render + " --frames 4 --aov id,depth --quiet").status, 0);
  std::ofstream(m_dir / "f" / "notes.txt") << "mine";
  std::ofstream(m_dir / "f" / "frame_final.png") << "not a numbered frame";
  const test::CommandRun run = kinray(render + " --frames 2");
  ASSERT_EQ(run.status, 0) << run.err;
  EXPECT_EQ(names("f"), (std::vector<std::string>{"frame_00000.png", "frame_00001.png",
                                                  "frame_final.png", "notes.txt"}));
  EXPECT_NE(run.out.find("removed 10 files of an earlier render"), std::string::npos) << run.out;
}

TEST_F(CliOutputs, InterruptingAVideoRenderLeavesNoTemporaryFile) {
  const std::string binary = KINRAY_BINARY;
  const std::string out = (m_dir / "v").string(), video = (m_dir / "v" / "clip.avi").string();
  fs::create_directories(out);
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    ::freopen("/dev/null", "w", stdout);
    ::freopen("/dev/null", "w", stderr);
    ::execl(binary.c_str(), binary.c_str(), "render", "wavy-sphere:triangles=2000", "--backend",
            "embree", "--size", "64x64", "--frames", "100000", "--out", out.c_str(), "--video",
            video.c_str(), "--quiet", static_cast<char*>(nullptr));
    ::_exit(127);
  }
  // Wait for the hidden temporary video to appear, then press Ctrl-C.
  const auto hidden = [&] {
    size_t count = 0;
    for (const auto& entry : fs::directory_iterator(out))
      if (entry.path().filename().string().front() == '.') ++count;
    return count;
  };
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (hidden() == 0 && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  ASSERT_GT(hidden(), 0u) << "the render never started its video";
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  ::kill(child, SIGINT);
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGINT) << "status " << status;
  EXPECT_EQ(hidden(), 0u) << "a temporary file was left behind";
  EXPECT_FALSE(fs::exists(video)) << "an unfinished video must not appear under its name";
}

TEST_F(CliOutputs, AFailedWriteIsExitStatusOneWithOneLine) {
  // /dev/full accepts the open and fails every write with ENOSPC: a full disk.
  for (const std::string& args :
       {std::string("render ") + kTiny + " --size 16x16 --frames 1 --quiet --out " + path("full") +
            " --stats /dev/full",
        std::string("diff ") + kTiny + " --size 16x16 --frames 1 --quiet --json /dev/full"}) {
    SCOPED_TRACE(args);
    const test::CommandRun run = kinray(args);
    EXPECT_EQ(run.status, 1) << run.err;
    EXPECT_EQ(run.err, "kinray: error: /dev/full: cannot write: No space left on device\n");
  }
}

TEST_F(CliOutputs, ParseErrorsAreKinraysOwnAndNameTheFlag) {
  const std::string render = std::string("render ") + kTiny + " --out " + path("base") + " ";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {render + "--frames many", "kinray: error: --frames: expected a whole number, got 'many'"},
      {render + "--zoom 1", "kinray: error: --zoom: no such flag for 'render'"},
      {render + "--frames 2 --frames 3", "kinray: error: --frames: given more than once"},
      {render + "--frames 2 --fps 3",
       "kinray: error: --frames: cannot be given together with --fps"},
      {render + "--fps fast", "kinray: error: --fps: expected a number, got 'fast'"},
      {render + "--size", "kinray: error: --size: needs a value"},
      {"render", "kinray: error: SCENE: missing"},
      {render + "extra", "kinray: error: render: unexpected argument 'extra'"},
      {"", "kinray: error: no command given"},
  };
  for (const auto& [args, line] : cases) {
    SCOPED_TRACE(args);
    const test::CommandRun run = kinray(args);
    EXPECT_EQ(run.status, 2);
    EXPECT_EQ(run.err.rfind(line, 0), 0u) << run.err;
    EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << run.err;
    for (const char* generic : {"Could not convert", "not expected", "At Most", "excludes"})
      EXPECT_EQ(run.err.find(generic), std::string::npos) << run.err;
  }
}

// Option values spelled once (util/enum_names.h): every command that takes the flag refuses a
// bad value at parse time with one line naming the flag and every allowed value, and exit 2.
TEST_F(CliOutputs, BadOptionValuesNameTheFlagAndTheAllowedValues) {
  const std::string scene = std::string(kTiny) + " ";
  const std::string render = "render " + scene + "--out " + path("base") + " ";
  const std::string sorts = "must be one of list, tournament, heap, got 'bubble'";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {render + "--sort bubble", "kinray: error: --sort: " + sorts},
      {"diff " + scene + "--sort bubble", "kinray: error: --sort: " + sorts},
      {"bench " + scene + "--sort bubble", "kinray: error: --sort: " + sorts},
      {render + "--sort LIST", "kinray: error: --sort: must be one of list, tournament, heap, got 'LIST'"},
      {render + "--embree-mode fast",
       "kinray: error: --embree-mode: must be one of rebuild, refit, got 'fast'"},
      {"diff " + scene + "--embree-mode 1",
       "kinray: error: --embree-mode: must be one of rebuild, refit, got '1'"},
      {render + "--packet 2", "kinray: error: --packet: must be one of 1, 4, 8, 16, got '2'"},
      {render + "--packet wide", "kinray: error: --packet: must be one of 1, 4, 8, 16, got 'wide'"},
      {render + "--shadow-tree octree",
       "kinray: error: --shadow-tree: must be one of aabb, boxtree, refit, brute, got 'octree'"},
  };
  for (const auto& [args, line] : cases) {
    SCOPED_TRACE(args);
    const test::CommandRun run = kinray(args);
    EXPECT_EQ(run.status, 2);
    EXPECT_EQ(run.err, line + "\n");
  }
  EXPECT_FALSE(fs::exists(path("base")));
}

// A backend names what it rejects by its config field (OptionError, util/input_error.h); the user
// reads the flag that set it.
TEST_F(CliOutputs, BackendErrorsNameTheFlag) {
  const std::string render = std::string("render ") + kTiny + " --size 16x16 --frames 1 --out " +
                             path("base") + " --quiet ";
  const test::CommandRun run = kinray(render + "--backend osmesa --shutter 0.5");
  EXPECT_EQ(run.status, 2);
  EXPECT_EQ(run.err,
            "kinray: error: --shutter: the osmesa backend has no motion blur (kinetic and embree "
            "have)\n");
}

TEST_F(CliOutputs, HelpListsTheAllowedValuesOfEnumFlags) {
  for (const char* command : {"render", "diff", "bench"}) {
    SCOPED_TRACE(command);
    const test::CommandRun run = kinray(std::string(command) + " --help");
    EXPECT_EQ(run.status, 0) << run.err;
    EXPECT_NE(run.out.find("--sort list|tournament|heap"), std::string::npos) << run.out;
  }
  const test::CommandRun render = kinray("render --help");
  EXPECT_NE(render.out.find("--embree-mode rebuild|refit"), std::string::npos) << render.out;
}

TEST_F(CliOutputs, VersionIsPrinted) {
  const test::CommandRun run = kinray("--version");
  EXPECT_EQ(run.status, 0);
  EXPECT_EQ(run.out.rfind("kinray ", 0), 0u) << run.out;
}

}  // namespace
}  // namespace kinray
