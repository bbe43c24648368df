#pragma once
// A one-line progress bar on stderr: frames done, elapsed time and time left. It draws only when
// enabled (by default: stderr is a terminal), so logs and pipes stay clean.
#include <chrono>
#include <cstddef>
#include <string>

namespace kinray {

class Progress {
 public:
  /// `total` frames; draws nothing unless `enabled`.
  Progress(size_t total, bool enabled);
  ~Progress();
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;

  /// True when stderr is a terminal (the default for `enabled`).
  [[nodiscard]] static bool stderr_is_terminal();
  /// Records `done` frames finished; redraws at most every 100 ms and on the last frame.
  void update(size_t done);
  /// Shows `text` (e.g. "loading SCENE...") in the bar's place until the bar or finish() replaces
  /// it: a long wait before the first frame is said, not silent.
  void note(const std::string& text);
  /// Clears the bar, so that what follows starts on a clean line.
  void finish();
  /// The bar as text, e.g. "[#####.....]  12/24 frames  1.3 s elapsed  1.3 s left" (for tests).
  [[nodiscard]] static std::string format(size_t done, size_t total, double elapsed_s,
                                          int width = 30);

 private:
  using Clock = std::chrono::steady_clock;
  size_t m_total = 0;
  bool m_enabled = false;
  bool m_drawn = false;
  Clock::time_point m_start, m_last_draw;
};

}  // namespace kinray
