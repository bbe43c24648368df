// Frame chunks: N chunks cover the schedule exactly once in nearly equal consecutive slices, bad
// flags are InputErrors naming the flag, and a chunked render's frames are bit for bit those of
// the whole render (the kinetic backend starting at the chunk's first frame).
#include <gtest/gtest.h>

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "renderer/job/frame_slice.h"
#include "renderer/job/render_job.h"
#include "tools/cli/frame_slice_flags.h"
#include "util/input_error.h"

namespace kinray {
namespace {

TEST(FrameSlice, ChunksCoverTheScheduleInNearlyEqualSlices) {
  for (size_t frames : {1u, 7u, 10u, 800u, 801u})
    for (size_t n = 1; n <= std::min<size_t>(frames, 13); ++n) {
      size_t next = 0;
      for (size_t i = 1; i <= n; ++i) {
        const FrameSlice slice = frame_slice(FrameChunk{i, n}, std::nullopt, frames);
        EXPECT_EQ(slice.begin, next);
        EXPECT_GE(slice.size(), frames / n);
        EXPECT_LE(slice.size(), frames / n + 1);
        next = slice.end;
      }
      EXPECT_EQ(next, frames);
    }
  const FrameSlice range = frame_slice(std::nullopt, FrameRange{3, 5}, 10);
  EXPECT_EQ(range.begin, 3u);
  EXPECT_EQ(range.end, 6u);
  EXPECT_EQ(frame_slice(std::nullopt, std::nullopt, 10).size(), 10u);
}

/// The slice the flags' text names in a schedule of `frames` frames, as `render` finds it: the
/// flags parsed (tools/cli), then sliced, an error of the library named by its flag.
FrameSlice slice_of_flags(const std::string& chunk, const std::string& range, size_t frames) {
  std::optional<FrameChunk> c;
  std::optional<FrameRange> r;
  if (!chunk.empty()) c = parse_chunk(chunk);
  if (!range.empty()) r = parse_frame_range(range);
  try {
    return frame_slice(c, r, frames);
  } catch (const OptionError& error) {
    const std::string flag = error.where() == "chunk"         ? "--chunk"
                             : error.where() == "frame_range" ? "--frame-range"
                                                              : "--chunk/--frame-range";
    throw InputError(flag, error.message());
  }
}

TEST(FrameSlice, BadFlagsNameTheFlag) {
  const std::vector<std::pair<std::pair<const char*, const char*>, const char*>> cases = {
      {{"0/3", ""}, "--chunk: I must lie in 1..N"},
      {{"4/3", ""}, "--chunk: I must lie in 1..N"},
      {{"1/x", ""}, "--chunk: expected I/N"},
      {{"1/-2", ""}, "--chunk: expected I/N"},
      {{"1/5", ""}, "--chunk: chunk 1/5 holds no frame"},
      {{"", "5:3"}, "--frame-range: A must not exceed B"},
      {{"", "2:4x"}, "--frame-range: expected A:B"},
      {{"", "2:4"}, "--frame-range: frame 4 is past the last frame"},
      {{"1/2", "0:1"}, "--chunk/--frame-range: give at most one"},
  };
  for (const auto& [flags, message] : cases) {
    try {
      (void)slice_of_flags(flags.first, flags.second, 4);
      ADD_FAILURE() << message << ": no error";
    } catch (const InputError& error) {
      EXPECT_EQ(std::string(error.what()).rfind(message, 0), 0u) << error.what();
    }
  }
}

/// Every frame a job renders, by its index in the schedule.
std::map<size_t, Frame> render_all(RenderParams params) {
  RenderJob job(params);
  auto backend = job.make_backend();
  std::map<size_t, Frame> frames;
  job.run(*backend, [&](size_t index, const Frame& frame) { frames[index] = frame; });
  return frames;
}

TEST(FrameSlice, ChunkedRendersAreBitIdenticalToTheWholeRender) {
  for (const char* scene : {"orbit:triangles=2000", "flythrough:triangles=2000"}) {
    RenderParams params;
    params.scene = scene;
    params.width = 48;
    params.height = 40;
    params.frames = 10;
    params.threads = 2;
    params.quiet = true;
    const std::map<size_t, Frame> whole = render_all(params);
    ASSERT_EQ(whole.size(), 10u);
    std::map<size_t, Frame> chunked;
    for (const char* chunk : {"1/3", "2/3", "3/3"}) {
      params.chunk = parse_chunk(chunk);
      for (auto& [index, frame] : render_all(params)) chunked[index] = std::move(frame);
    }
    params.chunk.reset();
    params.frame_range = FrameRange{7, 8};
    const std::map<size_t, Frame> range = render_all(params);
    ASSERT_EQ(chunked.size(), 10u);
    ASSERT_EQ(range.size(), 2u);
    for (const auto& [index, frame] : whole) {
      const Frame* in_range = range.count(index) ? &range.at(index) : nullptr;
      for (const Frame* other : std::vector<const Frame*>{&chunked.at(index), in_range}) {
        if (!other) continue;
        EXPECT_EQ(frame.time, other->time) << scene << " frame " << index;
        EXPECT_EQ(frame.object, other->object) << scene << " frame " << index;
        EXPECT_EQ(frame.prim, other->prim) << scene << " frame " << index;
        EXPECT_EQ(frame.depth, other->depth) << scene << " frame " << index;
        EXPECT_EQ(frame.color, other->color) << scene << " frame " << index;
      }
    }
  }
}

}  // namespace
}  // namespace kinray
