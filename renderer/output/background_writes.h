#pragma once
// A rendered frame's files written on a thread of their own while the next frame renders. The
// frame loop's backends and shading use every core, but encoding a PNG (the colour conversion and
// zlib's deflate) runs on one: written in line it was half of a slow-motion render's time
// (README, "What a slow-motion render costs beyond the grid"). One frame's writes at a time, in
// frame order, on a copy of the frame, so the loop may render into its own frame at once; a write
// that fails is rethrown, unchanged, by the next submit or by finish, so no later frame is
// written after it.
#include <cstddef>
#include <functional>
#include <future>
#include <utility>

#include "renderer/frame.h"

namespace kinray {

class BackgroundWrites {
 public:
  /// writer(index, frame) writes frame `index`'s files; it runs on the background thread.
  using Writer = std::function<void(size_t, const Frame&)>;

  explicit BackgroundWrites(Writer writer) : m_writer(std::move(writer)) {}
  BackgroundWrites(const BackgroundWrites&) = delete;
  BackgroundWrites& operator=(const BackgroundWrites&) = delete;
  /// Waits for a write still running; its error, if any, is dropped: the destructor runs without
  /// finish() only while another error is on its way out.
  ~BackgroundWrites() {
    if (m_pending.valid()) m_pending.wait();
  }

  /// Waits for the previous frame's writes (rethrowing their error), then starts frame `index`'s
  /// on a copy of `frame` (the copy reuses the last one's buffers).
  void submit(size_t index, const Frame& frame) {
    finish();
    m_frame = frame;
    m_pending = std::async(std::launch::async, [this, index] { m_writer(index, m_frame); });
  }

  /// Waits for the last frame's writes, rethrowing their error.
  void finish() {
    if (m_pending.valid()) m_pending.get();
  }

 private:
  Writer m_writer;
  Frame m_frame;  ///< the frame being written
  std::future<void> m_pending;
};

}  // namespace kinray
