#pragma once
// Warnings through a sink the caller owns. The library reports a documented repair of bad input
// (a model's bone weights normalized, a texture missing) as one line to warn(); by default it goes
// to stderr as "kinray: warning: <line>", and a caller that wants the lines (a test, a GUI, a
// farm's log) installs its own sink instead of capturing stderr.
//
//   std::vector<std::string> lines;
//   const ScopedWarningSink collect([&](const std::string& line) { lines.push_back(line); });
#include <functional>
#include <string>
#include <utility>

namespace kinray {

/// Receives one warning: a line without the "kinray: warning: " prefix and without a newline.
/// Calls are serialised, so a sink needs no lock of its own.
using WarningSink = std::function<void(const std::string& line)>;

/// Reports `line` to the installed sink (thread-safe).
void warn(const std::string& line);
/// Installs `sink` for the whole process and returns the one it replaces; an empty sink restores
/// the default, which prints "kinray: warning: <line>" on stderr.
WarningSink set_warning_sink(WarningSink sink);

/// Installs a sink while alive and puts the previous one back when it goes.
class ScopedWarningSink {
 public:
  explicit ScopedWarningSink(WarningSink sink) : m_previous(set_warning_sink(std::move(sink))) {}
  ~ScopedWarningSink() { set_warning_sink(std::move(m_previous)); }
  ScopedWarningSink(const ScopedWarningSink&) = delete;
  ScopedWarningSink& operator=(const ScopedWarningSink&) = delete;

 private:
  WarningSink m_previous;
};

}  // namespace kinray
