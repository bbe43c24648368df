// A frame's files written while the next frame renders: in frame order, from the frame as it was
// submitted, and a failed write stops the frames after it.
#include <gtest/gtest.h>

#include <stdexcept>
#include <string>
#include <vector>

#include "renderer/output/background_writes.h"
#include "util/input_error.h"

namespace kinray {
namespace {

Frame frame_at(double t) {
  Frame frame;
  frame.resize(3, 2);
  frame.time = t;
  frame.object[4] = uint32_t(10 * t);
  return frame;
}

TEST(BackgroundWrites, WritesEachFrameAsSubmittedInOrder) {
  std::vector<std::pair<size_t, uint32_t>> written;
  BackgroundWrites writes([&](size_t index, const Frame& frame) {
    written.emplace_back(index, frame.object[4]);
  });
  Frame frame = frame_at(1);
  for (size_t index = 0; index < 5; ++index) {
    frame = frame_at(double(index));
    writes.submit(index, frame);
    frame.object[4] = 999;  // the loop renders the next frame into its own buffers at once
  }
  writes.finish();
  ASSERT_EQ(written.size(), 5u);
  for (size_t index = 0; index < 5; ++index) {
    EXPECT_EQ(written[index].first, index);
    EXPECT_EQ(written[index].second, uint32_t(10 * index));
  }
  writes.finish();  // nothing pending: nothing to wait for
}

TEST(BackgroundWrites, AFailedWriteIsRethrownUnchangedAndStopsTheFramesAfterIt) {
  std::vector<size_t> written;
  BackgroundWrites writes([&](size_t index, const Frame&) {
    if (index == 1) throw InputError("out/frame_00001.png", "cannot write: disk full");
    written.push_back(index);
  });
  writes.submit(0, frame_at(0));
  writes.submit(1, frame_at(1));
  try {
    writes.submit(2, frame_at(2));
    FAIL() << "the failed write of frame 1 must be rethrown";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), "out/frame_00001.png: cannot write: disk full");
  }
  EXPECT_EQ(written, std::vector<size_t>{0});
}

TEST(BackgroundWrites, TheLastFramesFailureIsRethrownByFinish) {
  BackgroundWrites writes([](size_t, const Frame&) { throw std::runtime_error("no space"); });
  writes.submit(0, frame_at(0));
  EXPECT_THROW(writes.finish(), std::runtime_error);
  writes.finish();  // thrown once: the failed write is no longer pending
}

}  // namespace
}  // namespace kinray
