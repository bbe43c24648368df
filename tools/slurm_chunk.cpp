#include "tools/slurm_chunk.h"

#include <charconv>
#include <optional>
#include <system_error>

#include "util/input_error.h"

namespace kinray {
namespace {

std::optional<long long> whole(const char* text) {
  if (text == nullptr) return std::nullopt;
  const std::string_view view(text);
  long long value = 0;
  const auto [end, error] = std::from_chars(view.data(), view.data() + view.size(), value);
  if (error != std::errc() || end != view.data() + view.size()) return std::nullopt;
  return value;
}

}  // namespace

FrameChunk slurm_array_chunk(const EnvironmentLookup& lookup) {
  const auto read = [&](const char* name) -> std::optional<long long> {
    const char* text = lookup(name);
    const std::optional<long long> value = whole(text);
    if (text != nullptr && !value)
      throw InputError("--chunk", std::string("slurm: ") + name + " is not a whole number: '" +
                                      std::string(text).substr(0, 40) + "'");
    return value;
  };
  const std::optional<long long> id = read("SLURM_ARRAY_TASK_ID");
  if (!id)
    throw InputError("--chunk",
                     "slurm: not a task of a Slurm job array (SLURM_ARRAY_TASK_ID is not set); "
                     "give --chunk I/N");
  const std::optional<long long> min = read("SLURM_ARRAY_TASK_MIN");
  const std::optional<long long> count = read("SLURM_ARRAY_TASK_COUNT");
  if (!min || !count || *count < 1)
    throw InputError("--chunk",
                     "slurm: SLURM_ARRAY_TASK_MIN and SLURM_ARRAY_TASK_COUNT are not set");
  const long long step = read("SLURM_ARRAY_TASK_STEP").value_or(1);
  const long long offset = *id - *min;
  if (step < 1 || offset < 0 || offset % step != 0 || offset / step >= *count)
    throw InputError("--chunk", "slurm: task " + std::to_string(*id) +
                                    " is not on one evenly spaced range of array indices (min " +
                                    std::to_string(*min) + ", step " + std::to_string(step) + ", " +
                                    std::to_string(*count) + " tasks); give --chunk I/N");
  return FrameChunk{size_t(offset / step + 1), size_t(*count)};
}

}  // namespace kinray
