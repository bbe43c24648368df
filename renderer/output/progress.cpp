#include "renderer/output/progress.h"

#include <unistd.h>

#include <cmath>
#include <cstdio>

#include "util/fork_gate.h"

namespace kinray {
namespace {

std::string format_seconds(double s) {
  char text[32];
  if (!std::isfinite(s)) return "?";
  if (s < 60)
    std::snprintf(text, sizeof text, "%.1f s", s);
  else if (s < 3600)
    std::snprintf(text, sizeof text, "%dm%02ds", int(s) / 60, int(s) % 60);
  else
    std::snprintf(text, sizeof text, "%dh%02dm", int(s) / 3600, int(s) / 60 % 60);
  return text;
}

}  // namespace

Progress::Progress(size_t total, bool enabled)
    : m_total(total), m_enabled(enabled), m_start(Clock::now()), m_last_draw(m_start) {}

Progress::~Progress() {
  finish();
}

void Progress::draw(const std::string& line) {
  std::lock_guard lock(m_mutex);
  m_drawn = true;
  std::fprintf(stderr, "\r%s\033[K", line.c_str());
  std::fflush(stderr);
}

void Progress::stop_ticker() {
  if (!m_ticker.joinable()) return;
  {
    std::lock_guard lock(m_mutex);
    m_ticking = false;
  }
  m_wake.notify_all();
  m_ticker.join();
}

bool Progress::stderr_is_terminal() {
  return ::isatty(STDERR_FILENO) == 1;
}

std::string Progress::format(size_t done, size_t total, double elapsed_s, int width) {
  const double fraction = total == 0 ? 1.0 : double(done) / double(total);
  const int filled = int(std::lround(fraction * width));
  const double left = done == 0 ? NAN : elapsed_s * double(total - done) / double(done);
  char counts[64];
  std::snprintf(counts, sizeof counts, " %zu/%zu frames  ", done, total);
  // Appended piece by piece: GCC 12 warns (-Wrestrict, a false positive) on "[" + std::string.
  std::string line;
  line.reserve(size_t(width) + 80);
  line.append(1, '[').append(size_t(filled), '#').append(size_t(width - filled), '.').append(1, ']');
  line.append(counts).append(format_seconds(elapsed_s)).append(" elapsed  ");
  line.append(format_seconds(left)).append(" left");
  return line;
}

std::string Progress::format_working(const std::string& text, double fraction, double elapsed_s) {
  std::string line = text;
  if (fraction >= 0) {
    char percent[16];
    std::snprintf(percent, sizeof percent, " %d%%", int(std::floor(100 * fraction)));
    line += percent;
  }
  return line + "  " + format_seconds(elapsed_s);
}

void Progress::update(size_t done) {
  if (!m_enabled) return;
  stop_ticker();
  const Clock::time_point now = Clock::now();
  if (done < m_total && m_drawn && now - m_last_draw < std::chrono::milliseconds(100)) return;
  m_last_draw = now;
  m_drawn = true;
  const double elapsed = std::chrono::duration<double>(now - m_start).count();
  std::fprintf(stderr, "\r%s\033[K", format(done, m_total, elapsed).c_str());
  std::fflush(stderr);
}

void Progress::note(const std::string& text) {
  if (!m_enabled) return;
  stop_ticker();
  draw(text);
}

void Progress::working(const std::string& text, const WorkProgress* work) {
  if (!m_enabled) return;
  stop_ticker();
  draw(text);
  m_ticking = true;
  m_ticker = start_thread([this, text, work, start = Clock::now()] {
    std::unique_lock lock(m_mutex);
    while (!m_wake.wait_for(lock, std::chrono::milliseconds(250), [this] { return !m_ticking; })) {
      const ThreadBusy busy;  // a model is read in a forked child meanwhile (model_guard.h)
      const double elapsed = std::chrono::duration<double>(Clock::now() - start).count();
      const char* step = work ? work->step.load(std::memory_order_relaxed) : nullptr;
      const std::string line =
          format_working(step ? text + " " + step : text, work ? work->fraction() : -1, elapsed);
      std::fprintf(stderr, "\r%s\033[K", line.c_str());
      std::fflush(stderr);
    }
  });
}

void Progress::finish() {
  if (!m_enabled) return;
  stop_ticker();
  if (!m_drawn) return;
  std::fprintf(stderr, "\r\033[K");
  std::fflush(stderr);
  m_drawn = false;
}

}  // namespace kinray
