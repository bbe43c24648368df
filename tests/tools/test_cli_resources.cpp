// Requests that cannot fit in memory are refused before any work, naming the flag and the
// estimate; an allocation that fails anyway is one line and exit status 1; bench checks every
// configuration of its sweeps before the first one runs.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "renderer/job/memory_estimate.h"
#include "tests/address_sanitizer.h"
#include "tests/tools/kinray_process.h"

namespace kinray {
namespace {

namespace fs = std::filesystem;

class CliResources : public test::CommandTest {};

TEST_F(CliResources, RequestsThatCannotFitAreRefusedNamingTheFlag) {
  const std::optional<double> available = available_memory_bytes();
  ASSERT_TRUE(available.has_value()) << "/proc/meminfo has no MemAvailable";
  const std::string out = " --out '" + (m_dir / "f").string() + "'";
  struct Case {
    std::string args, where;
    double needs;  // bytes the estimate gives (a lower bound of what the render would take)
  };
  const std::vector<Case> cases = {
      {"render wavy-sphere:triangles=50000000", "wavy-sphere:triangles=50000000", 7e10},
      // the kinetic grid's pixel entries do not fit (auto would render it with Embree)
      {"render wavy-sphere --backend kinetic --size 16384x16384", "--size", 4e10},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.args);
    if (*available > c.needs) {
      std::cout << "[ NOTE     ] " << c.args << " fits in this machine's memory: not run\n";
      continue;
    }
    const test::CommandRun run = kinray(c.args + out);
    EXPECT_EQ(run.status, 2);
    EXPECT_EQ(run.err.rfind("kinray: error: " + c.where + ": this render needs about ", 0), 0u)
        << run.err;
    EXPECT_NE(run.err.find("GB available"), std::string::npos) << run.err;
    EXPECT_FALSE(fs::exists(m_dir / "f"));
  }
}

TEST_F(CliResources, AnAllocationFailureIsOneLineAndStatusOne) {
  // Under ASan the program cannot even start in 1.2 GB of address space.
  if (test::kUnderAddressSanitizer) GTEST_SKIP() << test::kAddressSpaceLimitUnderAsan;
  // A 1.2 GB address-space limit, which the estimate (from physical memory) does not know of.
  const fs::path err = m_dir / "err.txt";
  const std::string command = "ulimit -v 1200000; '" + std::string(KINRAY_BINARY) +
                              "' render wavy-sphere:triangles=2000000 --frames 2 --size 64x64 -q "
                              "--out '" +
                              (m_dir / "f").string() + "' 2>'" + err.string() + "'";
  const int raw = std::system(command.c_str());
  ASSERT_TRUE(WIFEXITED(raw));
  EXPECT_EQ(WEXITSTATUS(raw), 1);
  EXPECT_EQ(test::read_text(err).rfind("kinray: error: out of memory: ", 0), 0u)
      << test::read_text(err);
}

TEST_F(CliResources, BenchChecksEverySweepBeforeTheFirstConfigurationRuns) {
  const std::string bench =
      "bench wavy-sphere:triangles=600 --size 16x16 --reference-frames 1 --embree-modes refit/1 ";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {bench + "--inbetweens 1,100000000", "--inbetweens"},
      {bench + "--thread-counts 1,5000", "--thread-counts"},
      {bench + "--repetitions 1000000000", "--repetitions"},
      {bench + "--triangles 100,60000000", "--triangles"},
      {"bench " + std::string(KINRAY_SOURCE_DIR) + "/scenes/examples/orbit.json --triangles 100",
       "--triangles"},
  };
  for (const auto& [args, flag] : cases) {
    SCOPED_TRACE(args);
    const test::CommandRun run = kinray(args);
    EXPECT_EQ(run.status, 2);
    EXPECT_EQ(run.err.rfind("kinray: error: " + flag + ": ", 0), 0u) << run.err;
    EXPECT_EQ(run.err.find("[1/"), std::string::npos) << "a configuration ran: " << run.err;
  }
}

}  // namespace
}  // namespace kinray
