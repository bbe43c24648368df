// kinray diff SCENE ...: renders every frame with the tested backend (default kinetic) and with a
// reference (--against embree | osmesa), classifies each differing pixel as a tie or a real
// mismatch (verification/image_diff.h), prints a table, writes heat maps and a JSON summary, and
// exits 0 only when every frame's real mismatches are within the budget. It takes the same scene,
// frame and backend flags as `kinray render`. See docs/verification.md.
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <stdexcept>

#include "renderer/output/image_io.h"
#include "renderer/output/output_check.h"
#include "renderer/output/progress.h"
#include "tools/cli_options.h"
#include "tools/commands.h"
#include "tools/option_scope.h"
#include "util/input_error.h"
#include "verification/antialiasing_diff.h"
#include "verification/image_diff.h"
#include "verification/shutter_diff.h"

namespace kinray {
namespace {

namespace fs = std::filesystem;

/// Real mismatches allowed per frame against OSMesa unless --budget says otherwise: 0.1% of the
/// frame's pixels. Measured on the built-in scenes at 512x512 (docs/verification.md): 0 real
/// mismatches per frame; the budget leaves room for what llvmpipe does differently by design --
/// vertices snapped to 1/256 pixel, which on long edges moves coverage by more than the tie zone,
/// depth interpolated from the snapped vertices, and the near-plane clip.
constexpr double kOsmesaBudgetFraction = 0.001;

/// Real mismatches allowed in each frame: a pixel count, or a fraction of the frame's pixels.
struct Budget {
  double count = 0;
  bool fraction = false;
  [[nodiscard]] double allowed(size_t pixels) const {
    return fraction ? std::floor(count * double(pixels)) : count;
  }
  [[nodiscard]] std::string describe() const {
    char text[64];
    if (fraction)
      std::snprintf(text, sizeof text, "%g%% of the pixels per frame", 100 * count);
    else
      std::snprintf(text, sizeof text, "%g per frame", count);
    return text;
  }
};

/// "N" (a whole number of pixels, >= 0) or "P%" (0 <= P <= 100).
Budget parse_budget(const std::string& text) {
  const bool percent = !text.empty() && text.back() == '%';
  const std::string number = percent ? text.substr(0, text.size() - 1) : text;
  size_t used = 0;
  double value = std::nan("");
  try {
    value = std::stod(number, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  const bool whole = percent || value == std::floor(value);
  if (number.empty() || used != number.size() || !std::isfinite(value) || value < 0 || !whole ||
      (percent && value > 100))
    throw InputError(
        "--budget",
        "expected a pixel count N >= 0 or a percentage P% (0..100) per frame, not '" + text + "'");
  return percent ? Budget{value / 100, true} : Budget{value, false};
}

struct DiffOptions {
  RenderOptions render;
  std::string against = "embree";
  std::string report;
  std::string budget;
  std::string json;
  /// --shutter: the reference's time samples per pixel; --aa exact: its antialiasing samples
  std::optional<int> reference_samples;
};

std::string numbered(const char* prefix, size_t index) {
  char name[64];
  std::snprintf(name, sizeof name, "%s_%05zu.png", prefix, index);
  return name;
}

void run_diff(const DiffOptions& options) {
  const RenderParams params = options.render.resolve();
  if (params.aa == Antialiasing::exact || params.aa_samples > 1) {
    // Judged by colour against a supersampled reference: the id budget and OSMesa do not apply.
    // The tested frames are --aa exact's, or the sampling peer's at --aa-samples.
    const char* flag = params.aa == Antialiasing::exact ? "--aa exact" : "--aa-samples";
    if (!options.budget.empty())
      throw InputError("--budget",
                       std::string("counts id mismatches; ") + flag + " is judged by colour error");
    if (options.against != "embree")
      throw InputError("--against",
                       std::string(flag) + " is compared with embree's supersampling only");
    return run_antialiasing_diff(
        params, {options.reference_samples.value_or(kAntialiasingReferenceSamples), options.report,
                 options.json});
  }
  if (params.shutter.enabled())
    return run_shutter_diff(params, {options.reference_samples.value_or(kShutterReferenceSamples),
                                     options.report, options.json});
  if (options.reference_samples)
    throw InputError(
        "--reference-samples",
        "applies to --shutter, --aa exact or --aa-samples (the reference's samples), none of "
        "which is given");
  if (options.against != "embree" && options.against != "osmesa")
    throw InputError("--against",
                     "the reference must be embree or osmesa, not '" + options.against + "'");
  // OSMesa's fill rule differs by design, whichever side it is on.
  const bool rasterized = options.against == "osmesa" || params.backend == "osmesa";
  const Budget budget = options.budget.empty()
                            ? (rasterized ? Budget{kOsmesaBudgetFraction, true} : Budget{0, false})
                            : parse_budget(options.budget);
  check_options_apply(params, std::array{params.backend, options.against});
  if (!options.report.empty()) check_output_folder(options.report, "--report");
  if (!options.json.empty()) check_output_file(options.json, "--json");

  RenderJob job(params);
  std::unique_ptr<Backend> tested = job.make_backend();
  std::unique_ptr<Backend> reference = job.make_backend(options.against);

  // Everything is valid: from here on files are written.
  create_output_folder(options.report, "--report");
  create_output_folder(fs::path(options.json).parent_path(), "--json");
  const fs::path report(options.report);
  DiffSummary summary;
  summary.scene = params.scene;
  summary.tested = tested->name();
  summary.reference = reference->name();
  FrameComparator comparator(job.camera_space());
  Progress progress(job.frame_times().size(), !params.quiet && Progress::stderr_is_terminal());
  Frame a, b;
  tested->plan_frames(job.frame_times());
  reference->plan_frames(job.frame_times());
  for (size_t index = 0; index < job.frame_times().size(); ++index) {
    job.render_frame(*tested, index, a);
    job.render_frame(*reference, index, b);
    const FrameDiff diff = comparator.compare(a, b);
    FrameDiffSummary line = summarize(index, diff);
    line.color = compare_colors(a, b);
    if (!options.report.empty() && diff.mismatch_real + diff.mismatch_tie > 0) {
      line.heat_map = (report / numbered("diff", index)).string();
      write_heat_map(diff, line.heat_map, &b);
      if (diff.mismatch_real > 0) {
        write_color_png((report / numbered("tested", index)).string(), a);
        write_color_png((report / numbered("reference", index)).string(), b);
      }
    }
    summary.add(std::move(line));
    progress.update(index + 1);
  }
  progress.finish();

  if (!options.json.empty()) summary.write_json(options.json);
  if (!options.report.empty()) summary.write_json((report / "summary.json").string());
  size_t over = 0;
  for (const FrameDiffSummary& line : summary.per_frame)
    if (double(line.mismatch_real) > budget.allowed(line.pixels)) ++over;
  if (!params.quiet) {
    summary.print(std::cout);
    std::cout << "budget: " << budget.describe()
              << (over ? ", exceeded in " + std::to_string(over) + " frame(s)" : ", met") << "\n";
    std::cout.flush();
  }
  if (over > 0)
    throw std::runtime_error("diff: " + std::to_string(summary.mismatch_real) +
                             " real mismatches; " + std::to_string(over) + " of " +
                             std::to_string(summary.frames) + " frames exceed the budget of " +
                             budget.describe());
}

}  // namespace

void register_diff_command(CLI::App& app) {
  CLI::App* command = app.add_subcommand(
      "diff",
      "Render each frame with a backend and a reference, classify differing pixels as ties or real "
      "mismatches, and fail when real mismatches exceed the budget");
  auto options = std::make_shared<DiffOptions>();
  options->render.params.backend = "kinetic";  // the backend under test
  add_scene_options(*command, options->render);
  add_frame_options(*command, options->render);
  add_backend_options(*command, options->render);
  add_camera_options(*command, options->render.camera);
  command->add_option("--against", options->against, "The reference: embree | osmesa")
      ->capture_default_str();
  command->add_option(
      "--budget", options->budget,
      "Real mismatches allowed per frame: N pixels or P% of the pixels (default 0; 0.1% "
      "when osmesa is either side)");
  output_path(command->add_option(
      "--report", options->report,
      "Folder for heat maps (diff_NNNNN.png: yellow tie, red real, over the "
      "reference in dim grey), "
      "both shaded frames where a frame has real mismatches, and summary.json"));
  output_path(command->add_option("--json", options->json, "Write the summary as JSON to FILE"));
  command->add_option(
      "--reference-samples", options->reference_samples,
      "With --shutter: time samples per pixel of the Embree reference; with --aa exact: its "
      "antialiasing samples per pixel, a square (default 4096)");
  command->add_flag("-q,--quiet", options->render.params.quiet, "No progress bar and no table");
  command->callback([options] { run_diff(*options); });
}

}  // namespace kinray
