// The progress line's text: the frame bar, and the working line of a step before the first frame
// (elapsed seconds, and the share done when the step counts its work).
#include <gtest/gtest.h>

#include "renderer/output/progress.h"
#include "util/work_progress.h"

namespace kinray {
namespace {

TEST(Progress, BarShowsFramesElapsedAndTimeLeft) {
  EXPECT_EQ(Progress::format(12, 24, 1.3, 10), "[#####.....] 12/24 frames  1.3 s elapsed  1.3 s left");
  EXPECT_EQ(Progress::format(0, 24, 0.0, 4), "[....] 0/24 frames  0.0 s elapsed  ? left");
}

TEST(Progress, WorkingLineShowsTheShareDoneWhenKnown) {
  EXPECT_EQ(Progress::format_working("loading x...", -1, 2.46), "loading x...  2.5 s");
  EXPECT_EQ(Progress::format_working("initialising the kinetic grid...", 0.4219, 3.14),
            "initialising the kinetic grid... 42%  3.1 s");
  EXPECT_EQ(Progress::format_working("step", 1.0, 75), "step 100%  1m15s");
}

TEST(WorkProgress, FractionIsUnknownUntilTheTotalIsSetAndNeverAboveOne) {
  WorkProgress work;
  EXPECT_LT(work.fraction(), 0);
  work.total = 200;
  work.done = 50;
  EXPECT_DOUBLE_EQ(work.fraction(), 0.25);
  work.done = 250;  // a later insertion counted past the start's total
  EXPECT_DOUBLE_EQ(work.fraction(), 1.0);
}

}  // namespace
}  // namespace kinray
