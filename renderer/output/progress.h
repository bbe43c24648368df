#pragma once
// A one-line progress bar on stderr: frames done, elapsed time and time left. It draws only when
// enabled (by default: stderr is a terminal), so logs and pipes stay clean. Before the first
// frame, a long step (loading, the kinetic grid's initialisation) is shown as a line that a
// background thread redraws with the step's elapsed time and, when the step counts its work,
// how much of it is done.
#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <mutex>
#include <string>
#include <thread>

#include "util/work_progress.h"

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
  /// Like note(), and redrawn every 250 ms until the next call: `text`, the step `work` is on and
  /// the share of it done (when `work` is given and knows them), and the seconds since this call,
  /// e.g. "initialising the kinetic grid... scan conversion 42%  3.1 s". `work` must outlive the
  /// call's step.
  void working(const std::string& text, const WorkProgress* work = nullptr);
  /// Clears the bar, so that what follows starts on a clean line.
  void finish();
  /// The bar as text, e.g. "[#####.....]  12/24 frames  1.3 s elapsed  1.3 s left" (for tests).
  [[nodiscard]] static std::string format(size_t done, size_t total, double elapsed_s,
                                          int width = 30);
  /// The working line, e.g. "loading X...  2.5 s" or "initialising... 42%  3.1 s" (for tests);
  /// `fraction` < 0 when unknown.
  [[nodiscard]] static std::string format_working(const std::string& text, double fraction,
                                                  double elapsed_s);

 private:
  using Clock = std::chrono::steady_clock;
  void draw(const std::string& line);
  void stop_ticker();

  size_t m_total = 0;
  bool m_enabled = false;
  bool m_drawn = false;
  Clock::time_point m_start, m_last_draw;
  std::mutex m_mutex;  ///< one line drawn at a time, by the caller or the ticker
  std::condition_variable m_wake;
  bool m_ticking = false;
  std::thread m_ticker;
};

}  // namespace kinray
