#pragma once
// `--chunk I/N` and `--frame-range A:B`: the render-farm flags of `render`, which name a slice of
// the frame schedule (renderer/job/frame_slice.h).
#include <string>

#include "renderer/job/frame_slice.h"

namespace kinray {

/// Parses "I/N" with 1 <= I <= N. Throws InputError naming --chunk.
[[nodiscard]] FrameChunk parse_chunk(const std::string& text);
/// Parses "A:B" with A <= B (frame indices, both included). Throws InputError naming
/// --frame-range.
[[nodiscard]] FrameRange parse_frame_range(const std::string& text);

}  // namespace kinray
