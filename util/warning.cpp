#include "util/warning.h"

#include <iostream>
#include <mutex>
#include <utility>

namespace kinray {
namespace {

std::mutex& sink_mutex() {
  static std::mutex mutex;
  return mutex;
}

WarningSink& installed_sink() {
  static WarningSink sink;
  return sink;
}

}  // namespace

void warn(const std::string& line) {
  const std::lock_guard lock(sink_mutex());
  const WarningSink& sink = installed_sink();
  if (sink) return sink(line);
  std::cerr << "kinray: warning: " << line << std::endl;
}

WarningSink set_warning_sink(WarningSink sink) {
  const std::lock_guard lock(sink_mutex());
  return std::exchange(installed_sink(), std::move(sink));
}

}  // namespace kinray
