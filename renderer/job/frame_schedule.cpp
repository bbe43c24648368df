#include "renderer/job/frame_schedule.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <sstream>
#include <tuple>

#include "util/input_error.h"

namespace kinray {
namespace {

std::string format(double x) {
  std::ostringstream out;
  out << x;
  return out.str();
}

bool parse_number(const std::string& text, double& value) {
  if (text.empty() || std::isspace(static_cast<unsigned char>(text.front()))) return false;
  char* end = nullptr;
  value = std::strtod(text.c_str(), &end);
  return end == text.c_str() + text.size();
}

void check_count(size_t count, const char* field) {
  if (count > kMaxFrameCount)
    throw OptionError(field, "asks for " + std::to_string(count) +
                                 " frames, more than the limit of " +
                                 std::to_string(kMaxFrameCount));
}

}  // namespace

std::pair<double, double> parse_time_range(const std::string& text) {
  const size_t colon = text.find(':');
  double a = 0, b = 0;
  if (colon == std::string::npos || !parse_number(text.substr(0, colon), a) ||
      !parse_number(text.substr(colon + 1), b))
    throw InputError("--time", "expected A:B with two numbers, got '" + text + "'");
  const std::pair<double, double> range{a, b};
  FrameScheduleParams params;
  params.time = range;
  validate(params);
  return range;
}

void validate(const FrameScheduleParams& params) {
  const int given = int(params.frames.has_value()) + int(params.fps.has_value()) +
                    int(params.inbetweens.has_value());
  if (given > 1) throw InputError("--frames/--fps/--inbetweens", "give at most one of them");
  if (params.frames && *params.frames < 1)
    throw OptionError("frames", "must be at least 1, got " + std::to_string(*params.frames));
  if (params.fps && !(std::isfinite(*params.fps) && *params.fps > 0))
    throw OptionError("fps", "must be a finite number > 0, got " + format(*params.fps));
  if (params.inbetweens && *params.inbetweens < 1)
    throw OptionError("inbetweens",
                      "must be at least 1, got " + std::to_string(*params.inbetweens));
  if (params.time) {
    const auto [a, b] = *params.time;
    if (!std::isfinite(a) || !std::isfinite(b))
      throw OptionError("time", "A and B must be finite numbers");
    if (!(a < b))
      throw OptionError("time", "A must be less than B, got " + format(a) + ":" + format(b));
  }
  if (params.frames) check_count(size_t(*params.frames), "frames");
  if (params.inbetweens) check_count(size_t(*params.inbetweens), "inbetweens");
}

std::vector<double> frame_times(std::span<const double> key_times,
                                const FrameScheduleParams& params) {
  validate(params);
  if (key_times.empty()) throw InputError("", "the scene has no shot to render");
  const double shot_begin = key_times.front(), shot_end = key_times.back();
  double begin = shot_begin, end = shot_end;
  if (params.time) {
    std::tie(begin, end) = *params.time;
    if (begin < shot_begin || end > shot_end)
      throw OptionError("time", "[" + format(begin) + ", " + format(end) +
                                    "] is not inside the shot [" + format(shot_begin) + ", " +
                                    format(shot_end) + "]");
  }
  std::vector<double> grid = {begin};
  for (double t : key_times)
    if (t > begin && t < end) grid.push_back(t);
  grid.push_back(end);

  std::vector<double> times;
  if (params.fps) {
    const double fps = *params.fps;
    const double first = std::ceil(begin * fps), last = std::floor(end * fps);
    if (!(last - first < double(kMaxFrameCount))) check_count(kMaxFrameCount + 1, "fps");
    // k / F rounds, so look one step beyond each end and keep what lies inside [begin, end].
    for (double k = first - 1; k <= last + 1; k += 1) {
      const double t = k / fps;
      if (t >= begin && t <= end) times.push_back(t);
    }
    if (times.empty())
      throw OptionError("fps", "no multiple of 1/" + format(fps) + " s lies in the shot [" +
                                   format(begin) + ", " + format(end) + "]");
    check_count(times.size(), "fps");
  } else if (params.inbetweens) {
    const int k_per_interval = *params.inbetweens;
    check_count((grid.size() - 1) * size_t(k_per_interval) + 1, "inbetweens");
    for (size_t k = 0; k + 1 < grid.size(); ++k)
      for (int m = 0; m < k_per_interval; ++m)
        times.push_back(grid[k] + m * (grid[k + 1] - grid[k]) / k_per_interval);
    times.push_back(grid.back());
  } else {
    const int n = params.frames.value_or(kDefaultFrameCount);
    times.resize(size_t(n));
    for (int m = 0; m < n; ++m)
      times[size_t(m)] = n == 1 ? begin : begin + (end - begin) * m / (n - 1);
    if (n > 1) times.back() = end;
  }
  return times;
}

size_t key_intervals_spanned(std::span<const double> frames, std::span<const double> key_times) {
  if (frames.size() < 2) return 1;
  const auto inside = std::upper_bound(key_times.begin(), key_times.end(), frames.front());
  const auto beyond = std::lower_bound(key_times.begin(), key_times.end(), frames.back());
  return size_t(std::max<std::ptrdiff_t>(beyond - inside, 0)) + 1;
}

}  // namespace kinray
