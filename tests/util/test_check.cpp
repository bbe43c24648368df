#include <gtest/gtest.h>

#include <cstdint>

#include "kinetic/sort/depth_sort_kind.h"
#include "util/check.h"

namespace kinray {
namespace {

TEST(CheckDeathTest, ComparisonsPrintTheExpressionAndBothValues) {
  const int events = 3;
  const size_t live = 7;
  EXPECT_DEATH(KINRAY_CHECK_EQ(events + 1, 5), "events \\+ 1 == 5 \\(4 vs 5\\)");
  EXPECT_DEATH(KINRAY_CHECK_LT(live, size_t(2)), "live < size_t\\(2\\) \\(7 vs 2\\)");
  EXPECT_DEATH(KINRAY_CHECK_GE(-0.5, 0.25), "-0.5 >= 0.25 \\(-0.5 vs 0.25\\)");
  EXPECT_DEATH(KINRAY_CHECK_NE(DepthSortKind::kHeap, DepthSortKind::kHeap), "\\(2 vs 2\\)");
  EXPECT_DEATH(KINRAY_CHECK_GT(int64_t(-4), int64_t(-3)), "\\(-4 vs -3\\)");
}

TEST(Check, PassingComparisonsEvaluateEachOperandOnce) {
  int calls = 0;
  auto next = [&] { return ++calls; };
  KINRAY_CHECK_EQ(next(), 1);
  KINRAY_CHECK_LE(next(), 2);
  KINRAY_CHECK_GT(next(), 2);
  EXPECT_EQ(calls, 3);
}

}  // namespace
}  // namespace kinray
