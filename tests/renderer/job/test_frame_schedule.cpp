// Frame times from --frames, --fps, --inbetweens and --time on known key grids.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "renderer/job/frame_schedule.h"
#include "util/input_error.h"

namespace kinray {
namespace {

FrameScheduleParams frames(int n) {
  FrameScheduleParams p;
  p.frames = n;
  return p;
}
FrameScheduleParams fps(double f) {
  FrameScheduleParams p;
  p.fps = f;
  return p;
}
FrameScheduleParams inbetweens(int k) {
  FrameScheduleParams p;
  p.inbetweens = k;
  return p;
}

const std::vector<double> kGrid = {0, 1, 3};  // shot [0, 3], keys at 0, 1, 3

TEST(FrameSchedule, DefaultIs24FramesOverTheShot) {
  const std::vector<double> times = frame_times(kGrid, {});
  ASSERT_EQ(times.size(), 24u);
  EXPECT_EQ(times.front(), 0);
  EXPECT_EQ(times.back(), 3);
}

TEST(FrameSchedule, FramesIncludeBothEnds) {
  EXPECT_EQ(frame_times(std::vector<double>{0, 2}, frames(5)),
            (std::vector<double>{0, 0.5, 1, 1.5, 2}));
  EXPECT_EQ(frame_times(kGrid, frames(1)), (std::vector<double>{0}));
  EXPECT_EQ(frame_times(kGrid, frames(2)), (std::vector<double>{0, 3}));
  const std::vector<double> odd = frame_times(std::vector<double>{0.1, 0.7}, frames(7));
  ASSERT_EQ(odd.size(), 7u);
  EXPECT_EQ(odd.front(), 0.1);
  EXPECT_EQ(odd.back(), 0.7);
}

TEST(FrameSchedule, InbetweensSubdivideEveryKeyInterval) {
  EXPECT_EQ(frame_times(kGrid, inbetweens(4)),
            (std::vector<double>{0, 0.25, 0.5, 0.75, 1, 1.5, 2, 2.5, 3}));
  EXPECT_EQ(frame_times(kGrid, inbetweens(1)), kGrid);
}

TEST(FrameSchedule, FpsTakesMultiplesOfThePeriodInsideTheShot) {
  EXPECT_EQ(frame_times(std::vector<double>{0.1, 1}, fps(4)),
            (std::vector<double>{0.25, 0.5, 0.75, 1}));
  EXPECT_EQ(frame_times(kGrid, fps(1)), (std::vector<double>{0, 1, 2, 3}));
  EXPECT_EQ(frame_times(kGrid, fps(24)).size(), 73u);
  EXPECT_THROW((void)frame_times(std::vector<double>{0.1, 0.2}, fps(1)), InputError);
}

TEST(FrameSchedule, TimeRestrictsTheShotAndTheKeyGrid) {
  FrameScheduleParams p = inbetweens(2);
  p.time = {0.5, 2};
  EXPECT_EQ(frame_times(kGrid, p), (std::vector<double>{0.5, 0.75, 1, 1.5, 2}));
  p = frames(4);
  p.time = {1, 2.5};
  EXPECT_EQ(frame_times(kGrid, p), (std::vector<double>{1, 1.5, 2, 2.5}));
  p.time = {2, 4};  // beyond the shot
  EXPECT_THROW((void)frame_times(kGrid, p), InputError);
}

TEST(FrameSchedule, RejectsBadValues) {
  EXPECT_THROW(validate(frames(0)), InputError);
  EXPECT_THROW(validate(frames(-3)), InputError);
  EXPECT_THROW(validate(fps(0)), InputError);
  EXPECT_THROW(validate(fps(-24)), InputError);
  EXPECT_THROW(validate(fps(std::nan(""))), InputError);
  EXPECT_THROW(validate(fps(std::numeric_limits<double>::infinity())), InputError);
  EXPECT_THROW(validate(inbetweens(0)), InputError);
  EXPECT_THROW(validate(frames(2'000'000)), InputError);
  FrameScheduleParams both = frames(3);
  both.fps = 24;
  EXPECT_THROW(validate(both), InputError);
  try {
    validate(frames(-3));
    ADD_FAILURE() << "frames -3 was accepted";
  } catch (const OptionError& e) {
    EXPECT_EQ(e.where(), "frames");  // the field; the command line names it --frames
  }
}

TEST(FrameSchedule, ParsesTimeRanges) {
  EXPECT_EQ(parse_time_range("0.5:2"), std::make_pair(0.5, 2.0));
  EXPECT_EQ(parse_time_range("-1:1e-1"), std::make_pair(-1.0, 0.1));
  for (const char* bad :
       {"", "1", "1:", ":2", "a:b", "2:1", "1:1", "nan:1", "0:inf", "1:2:3", " 1:2"})
    EXPECT_THROW((void)parse_time_range(bad), InputError) << bad;
}

}  // namespace
}  // namespace kinray
