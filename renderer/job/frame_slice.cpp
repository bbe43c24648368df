#include "renderer/job/frame_slice.h"

#include "util/input_error.h"

namespace kinray {

std::string to_string(const FrameChunk& chunk) {
  return std::to_string(chunk.index) + "/" + std::to_string(chunk.count);
}

std::string to_string(const FrameRange& range) {
  return std::to_string(range.first) + ":" + std::to_string(range.last);
}

void validate(const std::optional<FrameChunk>& chunk, const std::optional<FrameRange>& range) {
  if (chunk && (chunk->count < 1 || chunk->index < 1 || chunk->index > chunk->count))
    throw OptionError("chunk", "I must lie in 1..N, got '" + to_string(*chunk) + "'");
  if (range && range->first > range->last)
    throw OptionError("frame_range", "A must not exceed B, got '" + to_string(*range) + "'");
  if (chunk && range) throw OptionError("frame_slice", "give at most one of them");
}

FrameSlice frame_slice(const std::optional<FrameChunk>& chunk,
                       const std::optional<FrameRange>& range, size_t frame_count) {
  validate(chunk, range);
  if (chunk) {
    const size_t i = chunk->index, n = chunk->count;
    const FrameSlice slice{(i - 1) * frame_count / n, i * frame_count / n};
    if (slice.size() == 0)
      throw OptionError("chunk", "chunk " + to_string(*chunk) +
                                     " holds no frame: the schedule has only " +
                                     std::to_string(frame_count) + " frames");
    return slice;
  }
  if (range) {
    if (range->last >= frame_count)
      throw OptionError("frame_range", "frame " + std::to_string(range->last) +
                                           " is past the last frame of the schedule (" +
                                           std::to_string(frame_count - 1) + ")");
    return {range->first, range->last + 1};
  }
  return {0, frame_count};
}

}  // namespace kinray
