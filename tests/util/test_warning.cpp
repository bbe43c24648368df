#include <gtest/gtest.h>

#include <string>
#include <thread>
#include <vector>

#include "util/warning.h"

namespace kinray {
namespace {

TEST(Warning, TheDefaultSinkPrintsOneKinrayLineOnStderr) {
  // What the command line shows: this test checks stderr itself, so it captures it.
  ::testing::internal::CaptureStderr();
  warn("model.obj: the bone weights of 3 vertices do not sum to 1; normalized them");
  EXPECT_EQ(::testing::internal::GetCapturedStderr(),
            "kinray: warning: model.obj: the bone weights of 3 vertices do not sum to 1; "
            "normalized them\n");
}

TEST(Warning, AnInstalledSinkGetsTheLinesAndThePreviousOneComesBack) {
  std::vector<std::string> outer, inner;
  {
    const ScopedWarningSink collect_outer([&](const std::string& line) { outer.push_back(line); });
    warn("one");
    {
      const ScopedWarningSink collect_inner(
          [&](const std::string& line) { inner.push_back(line); });
      warn("two");
    }
    warn("three");
  }
  EXPECT_EQ(outer, (std::vector<std::string>{"one", "three"}));
  EXPECT_EQ(inner, (std::vector<std::string>{"two"}));
  ::testing::internal::CaptureStderr();
  warn("four");
  EXPECT_EQ(::testing::internal::GetCapturedStderr(), "kinray: warning: four\n");
}

TEST(Warning, CallsFromManyThreadsAreSerialised) {
  std::vector<std::string> lines;  // no lock here: the sink's calls are serialised
  const ScopedWarningSink collect([&](const std::string& line) { lines.push_back(line); });
  std::vector<std::thread> threads;
  for (int t = 0; t < 4; ++t)
    threads.emplace_back([t] {
      for (int i = 0; i < 250; ++i) warn("thread " + std::to_string(t));
    });
  for (std::thread& thread : threads) thread.join();
  EXPECT_EQ(lines.size(), 1000u);
}

}  // namespace
}  // namespace kinray
