#include "verification/bench_support.h"

#include <algorithm>
#include <chrono>
#include <sstream>

namespace kinray {

double now_ms() {
  return std::chrono::duration<double, std::milli>(
             std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

double median(std::vector<double> values) {
  if (values.empty()) return 0;
  std::sort(values.begin(), values.end());
  const size_t n = values.size();
  return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

std::string with_triangles(const std::string& spec, int triangles) {
  const size_t colon = spec.find(':');
  const std::string name = spec.substr(0, colon);
  std::vector<std::string> kept;
  if (colon != std::string::npos) {
    std::stringstream rest(spec.substr(colon + 1));
    for (std::string item; std::getline(rest, item, ',');)
      if (item.rfind("triangles=", 0) != 0 && !item.empty()) kept.push_back(item);
  }
  kept.push_back("triangles=" + std::to_string(triangles));
  std::string result = name + ":";
  for (size_t k = 0; k < kept.size(); ++k) result += (k ? "," : "") + kept[k];
  return result;
}

std::vector<size_t> spread(size_t frames, int count) {
  std::vector<size_t> indices;
  const size_t n = std::min(frames, size_t(std::max(count, 1)));
  for (size_t k = 0; k < n; ++k) indices.push_back(n == 1 ? 0 : k * (frames - 1) / (n - 1));
  indices.erase(std::unique(indices.begin(), indices.end()), indices.end());
  return indices;
}

}  // namespace kinray
