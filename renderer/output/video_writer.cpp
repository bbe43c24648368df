#include "renderer/output/video_writer.h"

#include <unistd.h>

#include <cctype>
#include <cmath>
#include <filesystem>
#include <span>
#include <stdexcept>
#include <system_error>

#include "renderer/output/image_io.h"
#include "util/input_error.h"

namespace kinray {
namespace {

std::string lower_extension(const std::string& path) {
  std::string extension = std::filesystem::path(path).extension().string();
  for (char& c : extension) c = char(std::tolower(static_cast<unsigned char>(c)));
  return extension;
}

}  // namespace

void VideoWriter::validate_path(const std::string& path) {
  const std::string extension = lower_extension(path);
  if (extension != ".mp4" && extension != ".avi")
    throw InputError("--video", "'" + path + "' must end in .mp4 or .avi");
  std::error_code error;
  if (std::filesystem::is_directory(path, error))
    throw InputError("--video", "'" + path + "' is a directory");
}

std::pair<int, int> VideoWriter::encoded_size(int width, int height) {
  return {width & ~1, height & ~1};
}

VideoWriter::VideoWriter(std::string path, int width, int height, double fps)
    : m_path(std::move(path)), m_width(width), m_height(height) {
  validate_path(m_path);
  const std::filesystem::path target(m_path);
  const std::string extension = lower_extension(m_path);
  // The temporary name keeps the extension: OpenCV picks the container from it.
  // Appended piece by piece: GCC 12 warns (-Wrestrict, a false positive) on "." + std::string.
  std::string name(1, '.');
  name.append(target.stem().string()).append(".tmp").append(std::to_string(::getpid()));
  m_temporary = (target.parent_path() / name.append(extension)).string();
  m_interrupt_cleanup.emplace(m_temporary);
  if (!(fps > 0) || !std::isfinite(fps)) fps = 24;
  const char* codecs_mp4[] = {"avc1", "mp4v"};
  const char* codecs_avi[] = {"MJPG"};
  const bool mp4 = extension == ".mp4";
  for (const char* codec :
       mp4 ? std::span<const char* const>(codecs_mp4) : std::span<const char* const>(codecs_avi)) {
    const int fourcc = cv::VideoWriter::fourcc(codec[0], codec[1], codec[2], codec[3]);
    try {
      if (m_writer.open(m_temporary, mp4 ? cv::CAP_FFMPEG : cv::CAP_ANY, fourcc, fps,
                        cv::Size(width, height))) {
        m_codec = codec;
        break;
      }
    } catch (const cv::Exception&) {
      // An encoder that throws counts as one that does not open; the next codec is tried.
    }
  }
  if (!m_writer.isOpened()) {
    std::error_code ignored;
    std::filesystem::remove(m_temporary, ignored);
    throw InputError(
        m_path, mp4 ? "cannot open an MP4 encoder (tried avc1 and mp4v through OpenCV's FFmpeg "
                      "backend); try an .avi file instead"
                    : "cannot open an MJPG encoder for this file");
  }
}

VideoWriter::~VideoWriter() {
  if (m_closed) return;
  m_writer.release();
  std::error_code ignored;
  std::filesystem::remove(m_temporary, ignored);
}

void VideoWriter::write(const Frame& frame) {
  if (frame.width != m_width || frame.height != m_height)
    throw std::runtime_error("video frame size differs from the video's size");
  m_writer.write(color_image(frame));
  ++m_frames;
}

void VideoWriter::write(const cv::Mat& bgr) {
  if (bgr.cols != m_width || bgr.rows != m_height || bgr.type() != CV_8UC3)
    throw std::runtime_error("video frame size differs from the video's size");
  m_writer.write(bgr);
  ++m_frames;
}

void VideoWriter::close() {
  if (m_closed) return;
  m_writer.release();
  m_closed = true;
  std::error_code error;
  std::filesystem::rename(m_temporary, m_path, error);
  if (error) {
    std::error_code ignored;
    std::filesystem::remove(m_temporary, ignored);
    throw std::runtime_error(m_path + ": cannot write: " + error.message());
  }
}

}  // namespace kinray
