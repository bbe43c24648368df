#pragma once
// Small helpers of the benchmarks (`kinray bench`, with the grid or with the kinetic trees).
#include <string>
#include <vector>

namespace kinray {

/// Milliseconds on the steady clock (differences only).
[[nodiscard]] double now_ms();
/// The median (0 for none).
[[nodiscard]] double median(std::vector<double> values);
/// `spec` with its triangles= parameter set to `triangles` ("wavy-sphere:duration=2" ->
/// "wavy-sphere:duration=2,triangles=N").
[[nodiscard]] std::string with_triangles(const std::string& spec, int triangles);
/// Evenly spread frame indices, at most `count` of them, first and last included.
[[nodiscard]] std::vector<size_t> spread(size_t frames, int count);

}  // namespace kinray
