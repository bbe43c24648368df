// kinray render SCENE ...: renders a scene to a PNG sequence (and optionally a video, ID and depth
// buffers, and a --stats JSON). Every flag is checked and the scene loaded before the first file
// is touched, so bad input never harms earlier output.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <system_error>
#include <utility>

#include "renderer/contact_frames.h"
#include "renderer/job/frame_schedule.h"
#include "renderer/job/render_forecast.h"
#include "renderer/output/background_writes.h"
#include "renderer/output/image_io.h"
#include "renderer/output/output_check.h"
#include "renderer/output/progress.h"
#include "renderer/output/video_writer.h"
#include "scenes/scene_loader.h"
#include "tools/cli_options.h"
#include "tools/commands.h"
#include "tools/frame_sequence.h"
#include "tools/option_scope.h"
#include "util/input_error.h"
#include "util/warning.h"

namespace kinray {
namespace {

/// The forecast speaks after the grid's first keyframe interval. With fewer frames than the
/// keyframe intervals they span, every event between two frames is processed before the second,
/// and on a large scene that first wait alone is long (BART robots, two frames: minutes), so the
/// user hears it before: when the frames are fewer than half the intervals and the scene's
/// triangles times those intervals exceed kLongAdvance.
void warn_before_a_long_advance(const RenderJob& job) {
  constexpr double kLongAdvance = 1e7;  // triangle-intervals (40,000 triangles over 250)
  std::vector<double> times;
  for (size_t index : job.frames_to_render()) times.push_back(job.frame_times()[index]);
  const std::vector<double> keys = job.scene().key_times();
  const size_t intervals = key_intervals_spanned(times, keys);
  if (2 * times.size() >= intervals ||
      double(job.scene().triangle_count()) * double(intervals) < kLongAdvance)
    return;
  warn(std::to_string(times.size()) + " frames over " + std::to_string(intervals) +
       " keyframe intervals: the kinetic grid processes every event of those intervals, Embree "
       "renders the frames alone; --backend auto or embree is likely much faster");
}

namespace fs = std::filesystem;

/// Frames per second for the video: --fps when given, else the mean spacing of the frame times.
double video_fps(const RenderParams& params, const std::vector<double>& times) {
  if (params.fps) return *params.fps;
  if (times.size() < 2 || !(times.back() > times.front())) return 24;
  return std::clamp(double(times.size() - 1) / (times.back() - times.front()), 1.0, 240.0);
}

/// A path as the file system will resolve it, for telling whether two names are one file.
fs::path resolved(const std::string& path) {
  std::error_code error;
  const fs::path absolute = fs::absolute(path, error);
  const fs::path canonical = fs::weakly_canonical(absolute, error);
  return error ? absolute.lexically_normal() : canonical;
}

/// A file output (--stats, --video) must be none of the render's other outputs: not the other
/// one (JSON would be written over the video), and not a numbered file in --out, which a frame
/// would overwrite or the clean-up would remove as an earlier render's.
void check_distinct_output(const std::string& path, const char* flag, const std::string& out) {
  const fs::path file = resolved(path);
  if (file.parent_path() == resolved(out) && is_frame_output(file.filename().string()))
    throw InputError(flag, "'" + path +
                               "' is named like one of the frames the render writes in "
                               "--out '" +
                               out + "'; give another name or folder");
}

/// Every output of the render, checked before the scene is loaded.
void check_output_paths(const std::string& out, const RenderParams& params) {
  check_output_folder(out, "--out");
  if (!params.stats.empty()) {
    check_output_file(params.stats, "--stats");
    check_distinct_output(params.stats, "--stats", out);
  }
  if (!params.video.empty()) {
    check_output_file(params.video, "--video");
    check_distinct_output(params.video, "--video", out);
  }
  if (!params.stats.empty() && !params.video.empty() &&
      resolved(params.stats) == resolved(params.video))
    throw InputError("--stats",
                     "'" + params.stats + "' is also the --video file; give each its own");
}

/// The summary's parenthesis after the total time: how much of it was loading, and the kinetic
/// backend's event count (from the backend's `stats`).
std::string summary_details(const RenderTimings& timings, const nlohmann::json& stats) {
  char text[128];
  std::snprintf(text, sizeof text, " (loading %.2f s", timings.load);
  std::string details = text;
  if (stats.contains("events") && stats["events"].contains("total"))
    details += ", " + std::to_string(stats["events"]["total"].get<uint64_t>()) + " kinetic events";
  return details + ")";
}

/// The --video writer (null without --video), its folder made; warns when the encoder's even
/// sides differ from the frames'.
std::unique_ptr<VideoWriter> open_video(const RenderParams& params, const RenderJob& job) {
  if (params.video.empty()) return nullptr;
  create_output_folder(fs::path(params.video).parent_path(), "--video");
  auto video = std::make_unique<VideoWriter>(params.video, params.width, params.height,
                                             video_fps(params, job.frame_times()));
  const auto [width, height] = VideoWriter::encoded_size(params.width, params.height);
  if (width != params.width || height != params.height)
    warn("--video: video encoders need even sides, so the video is " + std::to_string(width) +
         "x" + std::to_string(height) + " (the frames are " + std::to_string(params.width) + "x" +
         std::to_string(params.height) + "); give an even --size for a video of the frames' size");
  return video;
}

/// What a render wrote besides its frames, for the summary.
struct RenderOutputs {
  const std::string& folder;
  const std::vector<std::string>& stale;  ///< files of an earlier render removed
  size_t contact_frames = 0;              ///< frames with tinted contacts (--contacts)
  const VideoWriter* video = nullptr;
};

void print_summary(const RenderJob& job, const Backend& backend, const RenderTimings& timings,
                   const RenderOutputs& outputs) {
  const RenderParams& params = job.params();
  const size_t n = timings.frames;
  nlohmann::json stats;
  backend.write_stats(stats);
  std::printf("rendered %zu frame%s of %s (%zu triangles, %dx%d) with %s in %.2f s%s\n", n,
              n == 1 ? "" : "s", params.scene.c_str(), job.scene().triangle_count(), params.width,
              params.height, backend.name().c_str(), timings.total,
              summary_details(timings, stats).c_str());
  if (stats.contains("auto"))  // which backend rendered which frames, and why
    std::printf("auto:   %s\n", stats["auto"]["summary"].get<std::string>().c_str());
  const FrameSlice& slice = job.slice();
  const std::string last =
      slice.size() > 1 ? " .. " + numbered_file("frame", slice.end - 1, ".png") : "";
  std::string of_slice;
  if (params.chunk) of_slice = " (chunk " + to_string(*params.chunk) + ")";
  if (params.frame_range) of_slice = " (--frame-range " + to_string(*params.frame_range) + ")";
  std::printf("frames: %s/%s%s%s\n", outputs.folder.c_str(),
              numbered_file("frame", slice.begin, ".png").c_str(), last.c_str(), of_slice.c_str());
  if (params.skip_existing)
    std::printf("skipped %zu frame%s whose files were already there (--skip-existing)\n",
                slice.size() - n, slice.size() - n == 1 ? "" : "s");
  const std::vector<std::string>& stale = outputs.stale;
  if (!stale.empty())
    std::printf("removed %zu file%s of an earlier render from %s (%s%s)\n", stale.size(),
                stale.size() == 1 ? "" : "s", outputs.folder.c_str(), stale.front().c_str(),
                stale.size() > 1 ? (" .. " + stale.back()).c_str() : "");
  if (params.contacts)
    std::printf("contacts: triangles in contact tinted in %zu of %zu frames\n",
                outputs.contact_frames, n);
  if (outputs.video)
    std::printf("video:  %s (%s)\n", params.video.c_str(), outputs.video->codec().c_str());
  if (!params.stats.empty()) std::printf("stats:  %s\n", params.stats.c_str());
}

void run_render(const RenderParams& flags) {
  const bool automatic = flags.backend == "auto";
  if (automatic)
    check_options_apply(flags, std::array<std::string, 2>{"kinetic", "embree"});
  else
    check_options_apply(flags, std::array{flags.backend});
  const std::string out = output_folder(flags);
  check_output_paths(out, flags);
  // Loading a big model and building the kinetic grid take seconds before the first frame.
  Progress status(0, !flags.quiet && Progress::stderr_is_terminal());
  status.working("loading " + flags.scene + "...");
  RenderJob job(flags);
  const RenderParams& params = job.params();  // with the scene's own size and frame count
  size_t contact_frames = 0;
  if (params.contacts) {
    status.note("finding contacts...");
    std::vector<std::vector<uint64_t>> tint =
        contact_tint_frames(job.scene(), job.frame_times(), job.slice());
    contact_frames = size_t(std::count_if(tint.begin(), tint.end(), [](const auto& t) { return !t.empty(); }));
    job.set_contact_tint(std::move(tint));
  }
  // A frame's files appear under their names only once whole (written under a temporary name,
  // then renamed): a frame whose files are all there is done.
  std::vector<std::string> kept;
  if (params.skip_existing)
    job.skip_frames([&](size_t index) {
      const std::vector<std::string> names = frame_files(index, params.aov);
      const bool done = std::all_of(names.begin(), names.end(), [&](const std::string& name) {
        std::error_code error;
        return fs::is_regular_file(fs::path(out) / name, error);
      });
      if (done) kept.insert(kept.end(), names.begin(), names.end());
      return done;
    });
  std::unique_ptr<Backend> backend = job.make_backend();
  const bool kinetic = backend->name() == "kinetic";
  if (kinetic && !params.quiet) warn_before_a_long_advance(job);
  if (kinetic)
    status.working("initialising the kinetic grid...", backend->initialisation_progress());
  else
    status.finish();

  // Everything is valid: from here on files are written.
  create_output_folder(out, "--out");
  const std::unique_ptr<VideoWriter> video = open_video(params, job);
  const bool write_id = std::find(params.aov.begin(), params.aov.end(), "id") != params.aov.end();
  const bool write_depth =
      std::find(params.aov.begin(), params.aov.end(), "depth") != params.aov.end();
  const fs::path folder(out);
  std::vector<std::string> written = kept;
  const auto write = [&](const std::string& name, auto&& writer, const Frame& frame) {
    writer((folder / name).string(), frame);
    written.push_back(name);
  };
  // A frame's files are written while the next one renders (renderer/output/background_writes.h);
  // `written` is read only after run has waited for the last of them.
  BackgroundWrites writes([&](size_t index, const Frame& frame) {
    write(numbered_file("frame", index, ".png"), write_color_png, frame);
    if (write_id) write(numbered_file("id", index, ".png"), write_id_png, frame);
    if (write_depth) write(numbered_file("depth", index, ".tiff"), write_depth_tiff, frame);
    if (video) video->write(frame);
  });
  KineticForecast forecast;
  const auto frame_done = [&](size_t index, const Frame&) {
    if (index == job.frames_to_render().front())
      status.finish();  // the job's bar takes the line from here
    if (kinetic && !params.quiet)
      if (const std::optional<RenderForecast> slow = forecast.frame_done(job, index)) {
        status.finish();  // the bar's line, drawn again at the next frame
        warn(forecast_warning(*slow));
      }
  };
  const RenderTimings& timings = job.run(*backend, frame_done, &writes);
  status.finish();  // already cleared by the bar: only marks the note as gone
  if (video) video->close();
  if (!params.stats.empty()) {
    create_output_folder(fs::path(params.stats).parent_path(), "--stats");
    nlohmann::json stats = render_stats(job, *backend);
    if (video)
      stats["video"] = {
          {"path", params.video}, {"codec", video->codec()}, {"frames", video->frames_written()}};
    write_file_atomically(params.stats, stats.dump(2) + "\n");
  }
  // A slice of the schedule (--chunk, --frame-range) shares its folder with the other slices:
  // only a whole render owns the folder's numbered frames.
  const bool whole = job.slice().begin == 0 && job.slice().end == job.frame_times().size();
  const std::vector<std::string> stale =
      whole ? remove_stale_frames(folder, written) : std::vector<std::string>{};
  if (!params.quiet)
    print_summary(job, *backend, timings, {out, stale, contact_frames, video.get()});
}

}  // namespace

void register_render_command(CLI::App& app) {
  CLI::App* command = app.add_subcommand("render",
                                         "Render a scene to PNG frames out/<scene>/frame_00000.png "
                                         "... (and a video, ID/depth buffers, stats)");
  auto options = std::make_shared<RenderOptions>();
  options->params.backend = "auto";  // diff and bench name the backends they compare
  add_render_options(*command, *options);
  command
      ->add_option("--chunk", options->chunk,
                   "Render farms: only the I-th of N consecutive slices of the frames (I/N, "
                   "1-based; slurm: this Slurm array task's)")
      ->group("Frames");
  command
      ->add_option("--frame-range", options->frame_range,
                   "Render farms: only frames A..B of the schedule (A:B, 0-based, both included)")
      ->group("Frames");
  command
      ->add_flag("--skip-existing", options->params.skip_existing,
                 "Render farms: render only the frames whose files are missing (a resubmitted "
                 "chunk finishes what an interrupted one left)")
      ->group("Frames");
  command
      ->add_flag("--contacts", options->params.contacts,
                 "Tint the triangles in contact (collide --self) during each frame's window "
                 "[t - h/2, t + h/2), h the frame spacing")
      ->group("Frames");
  command->footer(describe_scene_spec_syntax());
  command->callback([options] { run_render(options->resolve()); });
}

}  // namespace kinray
