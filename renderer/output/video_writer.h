#pragma once
// Video output through OpenCV: .mp4 through its FFmpeg backend (H.264 'avc1', else MPEG-4 Part 2
// 'mp4v'), .avi as Motion JPEG. The video is written under a temporary name beside the target and
// renamed into place by close(), so an interrupted render never leaves a torn video.
#include <opencv2/videoio.hpp>
#include <optional>
#include <string>
#include <utility>

#include "renderer/frame.h"
#include "renderer/output/temporary_files.h"

namespace kinray {

class VideoWriter {
 public:
  /// Throws InputError naming --video unless `path` ends in .mp4 or .avi. Touches no file.
  static void validate_path(const std::string& path);

  /// The size of the video made of `width` x `height` frames: every encoder used (H.264, MPEG-4
  /// and, through FFmpeg, Motion JPEG) codes 4:2:0 chroma, so an odd last column or row is
  /// dropped (measured: 33x25 frames give 32x24 .mp4 and .avi videos).
  [[nodiscard]] static std::pair<int, int> encoded_size(int width, int height);

  /// Opens an encoder for `width` x `height` frames at `fps` frames per second. Throws InputError
  /// naming the path when no codec can be opened for it.
  VideoWriter(std::string path, int width, int height, double fps);
  /// Abandons an unfinished video (removes the temporary file).
  ~VideoWriter();
  VideoWriter(const VideoWriter&) = delete;
  VideoWriter& operator=(const VideoWriter&) = delete;

  /// Appends frame.color (converted to 8-bit sRGB).
  void write(const Frame& frame);
  /// Appends an 8-bit BGR image of the video's size (frames read back from PNG files).
  void write(const cv::Mat& bgr);
  /// Finishes the file and renames it to the target path.
  void close();
  /// The fourcc in use, e.g. "avc1".
  [[nodiscard]] const std::string& codec() const { return m_codec; }
  [[nodiscard]] int frames_written() const { return m_frames; }

 private:
  std::string m_path, m_temporary, m_codec;
  int m_width = 0, m_height = 0, m_frames = 0;
  std::optional<TemporaryFile> m_interrupt_cleanup;  ///< removes m_temporary on Ctrl-C
  cv::VideoWriter m_writer;
  bool m_closed = false;
};

}  // namespace kinray
