#pragma once
// Frame chunks for render farms: one job renders a consecutive slice of the frame schedule
// (`--chunk I/N`, the I-th of N nearly equal slices, or `--frame-range A:B`), its files numbered
// by their index in the whole schedule, so that the slices of N jobs together are the frames of
// one whole render (docs/render_farm.md).
#include <cstddef>
#include <string>
#include <utility>

namespace kinray {

/// Frames [begin, end) of the schedule.
struct FrameSlice {
  size_t begin = 0, end = 0;
  [[nodiscard]] size_t size() const { return end - begin; }
};

/// Parses "I/N" with 1 <= I <= N. Throws InputError naming --chunk.
[[nodiscard]] std::pair<size_t, size_t> parse_chunk(const std::string& text);
/// Parses "A:B" with 0 <= A <= B (frame indices, both included). Throws InputError naming
/// --frame-range.
[[nodiscard]] std::pair<size_t, size_t> parse_frame_range(const std::string& text);

/// The slice of a schedule of `frame_count` frames that `chunk` ("I/N") or `range` ("A:B") name
/// (both empty: every frame). Chunk I of N is [floor((I-1) F / N), floor(I F / N)). Throws
/// InputError naming the flag when both are given, a range reaches past the last frame or a
/// chunk holds no frame (N > F).
[[nodiscard]] FrameSlice frame_slice(const std::string& chunk, const std::string& range,
                                     size_t frame_count);

}  // namespace kinray
