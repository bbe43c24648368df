#pragma once
// Frame chunks for render farms: one job renders a consecutive slice of the frame schedule
// (`--chunk I/N`, the I-th of N nearly equal slices, or `--frame-range A:B`), its files numbered
// by their index in the whole schedule, so that the slices of N jobs together are the frames of
// one whole render (docs/render_farm.md).
#include <cstddef>
#include <optional>
#include <string>

namespace kinray {

/// Frames [begin, end) of the schedule.
struct FrameSlice {
  size_t begin = 0, end = 0;
  [[nodiscard]] size_t size() const { return end - begin; }
};

/// `--chunk I/N`: the I-th (1-based) of N nearly equal consecutive slices of the schedule.
struct FrameChunk {
  size_t index = 1, count = 1;
};
/// `--frame-range A:B`: frames A..B of the schedule, both included.
struct FrameRange {
  size_t first = 0, last = 0;
};

/// "I/N", as the flag is written.
[[nodiscard]] std::string to_string(const FrameChunk& chunk);
/// "A:B", as the flag is written.
[[nodiscard]] std::string to_string(const FrameRange& range);

/// Throws OptionError naming the field ("chunk", "frame_range") for a chunk outside 1..N or a
/// range that runs backwards: what can be checked without the schedule.
void validate(const std::optional<FrameChunk>& chunk, const std::optional<FrameRange>& range);

/// The slice of a schedule of `frame_count` frames that `chunk` or `range` name (neither: every
/// frame). Chunk I of N is [floor((I-1) F / N), floor(I F / N)). Throws OptionError naming the
/// field ("chunk", "frame_range", or "frame_slice" when both are given) for a bad value, a range
/// that reaches past the last frame or a chunk that holds no frame (N > F).
[[nodiscard]] FrameSlice frame_slice(const std::optional<FrameChunk>& chunk,
                                     const std::optional<FrameRange>& range, size_t frame_count);

}  // namespace kinray
