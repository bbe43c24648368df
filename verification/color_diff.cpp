#include "verification/color_diff.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "renderer/output/image_io.h"
#include "renderer/output/progress.h"
#include "verification/shutter_error.h"

namespace kinray {
namespace {

std::string numbered(const char* prefix, size_t index) {
  char name[64];
  std::snprintf(name, sizeof name, "%s_%05zu.png", prefix, index);
  return name;
}

}  // namespace

bool ColorTolerance::met(const ColorError& e) const {
  return std::sqrt(e.mse) <= rmse && e.max_error <= max_error;
}

ColorDiffFrames diff_frames_by_color(RenderJob& job, Backend& tested,
                                     const std::function<void(size_t, Frame&)>& reference,
                                     const ColorTolerance& tolerance, const std::string& report,
                                     bool quiet, const TiePixels& ties) {
  const std::filesystem::path folder(report);
  const size_t count = job.frame_times().size();
  Progress progress(count, !quiet && Progress::stderr_is_terminal());
  ColorDiffFrames out;
  Frame a, b;
  double squared = 0;
  for (size_t index = 0; index < count; ++index) {
    job.render_frame(tested, index, a);
    reference(index, b);
    const std::vector<uint8_t> aside = ties ? ties(index, a, b) : std::vector<uint8_t>{};
    const size_t tie_count = size_t(std::count(aside.begin(), aside.end(), uint8_t(1)));
    out.ties += tie_count;
    const ColorError error = compare_colors(a, b, ties ? &aside : nullptr);
    const double rmse = std::sqrt(error.mse);
    squared += error.mse;
    out.worst_rmse = std::max(out.worst_rmse, rmse);
    out.worst_max_error = std::max(out.worst_max_error, error.max_error);
    const bool met = tolerance.met(error);
    if (!met) ++out.outside;
    if (!report.empty()) {
      write_color_png((folder / numbered("tested", index)).string(), a);
      write_color_png((folder / numbered("reference", index)).string(), b);
      write_error_png(a, b, (folder / numbered("error", index)).string(), 10,
                      ties ? &aside : nullptr);
    }
    out.per_frame.push_back({{"frame", index},
                             {"time", job.frame_times()[index]},
                             {"rmse", rmse},
                             {"max_error", error.max_error},
                             {"ties", tie_count},
                             {"within_tolerance", met}});
    if (!quiet) {
      const std::string tie_note =
          tie_count > 0 ? "  (" + std::to_string(tie_count) + " ties aside)" : "";
      std::printf("frame %5zu  t=%-10g rmse %.3g  max %.3g%s%s\n", index, job.frame_times()[index],
                  rmse, error.max_error, tie_note.c_str(), met ? "" : "  OUTSIDE TOLERANCE");
      std::fflush(stdout);
    }
    progress.update(index + 1);
  }
  progress.finish();
  // Every frame has the same size, so the pooled mean square is the frames' mean (near enough
  // where a few ties are set aside).
  out.rmse = count ? std::sqrt(squared / double(count)) : 0;
  return out;
}

}  // namespace kinray
