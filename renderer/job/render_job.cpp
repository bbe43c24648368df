#include "renderer/job/render_job.h"

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <initializer_list>
#include <nlohmann/json.hpp>
#include <optional>
#include <system_error>
#include <tuple>

#include "renderer/antialiasing/pixel_samples.h"
#include "renderer/contact_tint.h"
#include "renderer/job/memory_estimate.h"
#include "renderer/output/progress.h"
#include "renderer/output/video_writer.h"
#include "renderer/shading.h"
#include "renderer/shadows/kinetic_shadow_tracer.h"
#include "renderer/shadows/lighting.h"
#include "renderer/shadows/shadow_rays.h"
#include "scenes/scene_loader.h"
#include "util/check.h"
#include "util/input_error.h"

namespace kinray {
namespace {

double now_s() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

/// The problem with `value` when it is none of `allowed`, else nothing: the flag parser and
/// validate() throw it naming the flag and the field respectively.
std::optional<std::string> not_one_of(const std::string& value,
                                      std::initializer_list<const char*> allowed) {
  std::string list;
  for (const char* a : allowed) {
    if (value == a) return std::nullopt;
    list += (list.empty() ? "" : ", ") + std::string(a);
  }
  return "must be one of " + list + ", got '" + value + "'";
}

}  // namespace

std::optional<std::string> aov_problem(const std::string& name) {
  return not_one_of(name, {"id", "depth"});
}

void validate(const RenderParams& params) {
  if (params.scene.empty()) throw InputError("SCENE", "no scene given");
  if (params.width < 1 || params.height < 1 || params.width > kMaxImageSide ||
      params.height > kMaxImageSide)
    throw OptionError("width", "width and height must lie in 1.." + std::to_string(kMaxImageSide) +
                                   ", got " + std::to_string(params.width) + "x" +
                                   std::to_string(params.height));
  validate(schedule_params(params));
  if (params.threads < 0 || params.threads > 4096)
    throw OptionError("threads",
                      "must lie in 0..4096 (0: all cores), got " + std::to_string(params.threads));
  if (!is_embree_packet_width(params.packet))
    throw OptionError("packet", "must be 1, 4, 8 or 16, got " + std::to_string(params.packet));
  for (const std::string& aov : params.aov)
    if (const auto problem = aov_problem(aov)) throw OptionError("aov", *problem);
  if (!std::isfinite(params.keyrate) || params.keyrate < 0 || params.keyrate > kMaxKeyrate)
    throw OptionError("keyrate", "must be a number in [0, 1e6] (0: the model's own keys)");
  if (params.skip_existing && !params.video.empty())
    throw InputError("--skip-existing",
                     "does not combine with --video (a video needs every frame): once every "
                     "chunk is done, assemble the frames with kinray video DIR --out FILE");
  if (!params.video.empty()) {
    VideoWriter::validate_path(params.video);
    if (params.width < 2 || params.height < 2)
      throw OptionError("video",
                        "video encoders need frames of at least 2x2 pixels, and --size is " +
                            std::to_string(params.width) + "x" + std::to_string(params.height));
  }
  if (params.lights.size() > kMaxLights)
    throw OptionError("lights", "at most " + std::to_string(kMaxLights) + " lights, got " +
                                    std::to_string(params.lights.size()));
  validate(params.chunk, params.frame_range);
  validate(params.shutter);
  check_aa_samples(params.aa_samples);
  if (params.aa == Antialiasing::exact && params.aa_samples > 1)
    throw OptionError("aa", "exact antialiasing needs no samples: drop --aa-samples");
  if (params.contacts && params.shutter.enabled())
    throw InputError("--contacts", "tints sharp frames; drop --shutter (motion blur) or --contacts");
}

FrameScheduleParams schedule_params(const RenderParams& params) {
  FrameScheduleParams schedule;
  schedule.frames = params.frames;
  schedule.fps = params.fps;
  schedule.inbetweens = params.inbetweens;
  schedule.time = params.time;
  return schedule;
}

BackendConfig backend_config(const RenderParams& params) {
  BackendConfig config;
  config.width = params.width;
  config.height = params.height;
  config.threads = params.threads;
  config.embree_build = params.embree_mode;
  config.embree_packet = params.packet;
  config.sort = params.sort;
  config.audit = params.audit;
  config.shadow_tree = params.shadow_tree;
  config.shutter = params.shutter;
  config.aa_samples = params.aa_samples;
  config.aa = params.aa;
  return config;
}

ModelOptions model_options(const RenderParams& params) {
  ModelOptions options;
  options.animation = params.animation;
  options.keyrate = params.keyrate;
  options.camera = model_camera_choice(params.camera);
  return options;
}

std::string scene_stem(const std::string& spec) {
  std::error_code error;
  // A file keeps its whole name (it may contain ':'); a built-in name drops its parameters.
  const std::string base =
      std::filesystem::exists(spec, error) ? spec : spec.substr(0, spec.find(':'));
  // A mesh sequence: a folder named with a trailing '/', or a glob whose wildcards name nothing.
  std::string trimmed = base;
  while (trimmed.size() > 1 && trimmed.back() == '/') trimmed.pop_back();
  std::erase_if(trimmed, [](char c) { return c == '*' || c == '?' || c == '[' || c == ']'; });
  std::string stem = std::filesystem::path(trimmed).stem().string();
  for (char& c : stem)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '_' && c != '.') c = '_';
  return stem.empty() || stem == "." || stem == ".." ? "scene" : stem;
}

std::string output_folder(const RenderParams& params) {
  return params.out.empty() ? (std::filesystem::path("out") / scene_stem(params.scene)).string()
                            : params.out;
}

RenderJob::RenderJob(RenderParams params) : m_params(std::move(params)), m_started(now_s()) {
  validate(m_params);
  check_render_memory(m_params, nullptr);  // a built-in that cannot fit is not built
  m_scene = load_scene(m_params.scene, model_options(m_params));
  apply_camera_choice(m_params.camera, m_scene, m_params.time);
  m_scene.validate(m_params.scene);
  if (!m_params.lights.empty()) m_scene.lights = m_params.lights;
  // The lit read-out traces its shadow rays through the kinetic tree at one time, and the space-
  // time box filter reads out at each pixel's own times.
  if (m_params.aa == Antialiasing::exact && m_params.shutter.enabled() && !m_scene.lights.empty())
    throw OptionError("aa",
                      "exact antialiasing under the shutter (--shutter) of a scene with lights is "
                      "not supported yet; --aa-samples N on the embree backend samples it");
  if (m_scene.lights.size() > kMaxLights)
    throw InputError(m_params.scene, "has " + std::to_string(m_scene.lights.size()) +
                                         " lights; at most " + std::to_string(kMaxLights) +
                                         " fit a frame's per-pixel light mask");
  // A scene that names its image size and frame count (BART) gets them unless flags say otherwise.
  if (m_params.scene_size && m_scene.image_width > 0)
    std::tie(m_params.width, m_params.height) = std::pair(m_scene.image_width, m_scene.image_height);
  if (!m_params.frames && !m_params.fps && !m_params.inbetweens && m_scene.frame_count > 0)
    m_params.frames = m_scene.frame_count;
  m_frame_times = kinray::frame_times(m_scene.key_times(), schedule_params(m_params));
  m_slice = frame_slice(m_params.chunk, m_params.frame_range, m_frame_times.size());
  for (size_t index = m_slice.begin; index < m_slice.end; ++index) m_to_render.push_back(index);
  if (m_params.shutter.enabled())
    m_windows = kinray::shutter_windows(m_frame_times, m_scene.key_times(), m_params.shutter.shutter);
  // Camera space holds the keys of the shot (--time) and its shutter windows only. Every chunk
  // of a farm render keeps the same keys, so that its frames are the single render's.
  std::pair<double, double> span =
      m_params.time.value_or(std::pair(m_scene.time_begin, m_scene.time_end));
  for (const ShutterWindow& window : m_windows)
    span = {std::min(span.first, window.open), std::max(span.second, window.close)};
  check_render_memory(m_params, &m_scene, span);
  m_camera_space = CameraSpaceScene::build(m_scene, span);
  m_lights = CameraSpaceLights(m_scene);
  m_timings.load = now_s() - m_started;
}

std::unique_ptr<Backend> RenderJob::make_backend(const std::string& name) {
  const double start = now_s();
  std::unique_ptr<Backend> backend = kinray::make_backend(name.empty() ? m_params.backend : name,
                                                          m_camera_space, backend_config(m_params));
  m_timings.setup += now_s() - start;
  return backend;
}

void RenderJob::set_contact_tint(std::vector<std::vector<uint64_t>> per_frame) {
  KINRAY_CHECK(per_frame.size() == m_frame_times.size());
  m_contact_tint = std::move(per_frame);
}

void RenderJob::render_frame(Backend& backend, size_t index, Frame& frame) {
  double start = now_s();
  if (!m_windows.empty()) {
    backend.render_shutter(m_windows.at(index), frame);
    m_timings.render += now_s() - start;
    return;
  }
  if (m_params.aa_samples > 1 || m_params.aa == Antialiasing::exact) {
    // The backend shades its samples or its squares' visible regions itself (supersampling with
    // shadow rays when the scene has lights).
    if (m_params.aa == Antialiasing::exact)
      backend.render_antialiased(m_frame_times.at(index), frame);
    else
      backend.render_supersampled(m_frame_times.at(index), frame);
    m_timings.render += now_s() - start;
    if (!m_contact_tint.empty()) tint_contacts(m_contact_tint.at(index), frame);
    return;
  }
  backend.render(m_frame_times.at(index), frame);
  m_timings.render += now_s() - start;
  start = now_s();
  if (m_lights.empty()) {
    shade_frame(m_camera_space, frame, m_params.threads);
  } else {
    ShadowTracer* tracer = backend.shadow_tracer();
    if (tracer == nullptr) {
      // A backend that traces no shadow rays (OSMesa) borrows Embree's occlusion rays.
      if (!m_shadow_helper)
        m_shadow_helper = kinray::make_backend("embree", m_camera_space, backend_config(m_params));
      m_shadow_helper->render(frame.time, m_shadow_scratch);
      tracer = m_shadow_helper->shadow_tracer();
    }
    shade_frame_lit(m_camera_space, m_lights, *tracer, frame, m_params.threads);
  }
  if (!m_contact_tint.empty()) tint_contacts(m_contact_tint.at(index), frame);
  m_timings.shade += now_s() - start;
}

void RenderJob::skip_frames(const std::function<bool(size_t index)>& done) {
  std::erase_if(m_to_render, done);
}

const RenderTimings& RenderJob::run(Backend& backend,
                                    const std::function<void(size_t, const Frame&)>& sink,
                                    BackgroundWrites* writes) {
  Progress progress(m_to_render.size(), !m_params.quiet && Progress::stderr_is_terminal());
  Frame frame;
  frame.resize(m_params.width, m_params.height);
  // The kinetic backend is built at the first time it renders: the first frame to render. The
  // bar is first drawn after it, so a command's note ("initialising the kinetic grid...") stays.
  std::vector<double> times;
  for (size_t index : m_to_render) times.push_back(m_frame_times[index]);
  backend.plan_frames(times);
  for (size_t index : m_to_render) {
    render_frame(backend, index, frame);
    const double start = now_s();
    if (sink) sink(index, frame);
    if (writes != nullptr) writes->submit(index, frame);
    m_timings.write += now_s() - start;
    ++m_timings.frames;
    progress.update(m_timings.frames);
  }
  if (writes != nullptr) {
    const double start = now_s();
    writes->finish();
    m_timings.write += now_s() - start;
  }
  progress.finish();
  m_timings.total = now_s() - m_started;
  return m_timings;
}

nlohmann::json render_stats(const RenderJob& job, const Backend& backend) {
  const RenderParams& params = job.params();
  const RenderTimings& timings = job.timings();
  nlohmann::json stats = {
      {"scene", params.scene},
      {"backend", backend.name()},
      {"frames", timings.frames},
      {"size", {{"width", params.width}, {"height", params.height}}},
      {"threads", params.threads},
      {"triangles", job.scene().triangle_count()},
      {"vertices", job.scene().vertex_count()},
      {"objects", job.scene().objects.size()},
      {"lights", job.scene().lights.size()},
      {"shot", {job.scene().time_begin, job.scene().time_end}},
      {"frame_times", job.frame_times()},
      {"slice",
       {{"first", job.slice().begin},
        {"last", job.slice().size() > 0 ? job.slice().end - 1 : job.slice().begin},
        {"chunk", params.chunk ? nlohmann::json(to_string(*params.chunk)) : nlohmann::json()},
        {"frame_range",
         params.frame_range ? nlohmann::json(to_string(*params.frame_range)) : nlohmann::json()},
        {"skipped", job.slice().size() - job.frames_to_render().size()}}},
      {"shutter", job.params().shutter.shutter},
      {"aa", antialiasing_name(params.aa)},
      {"time_s",
       {{"total", timings.total},
        {"load", timings.load},
        {"setup", timings.setup},
        {"render", timings.render},
        {"shade", timings.shade},
        {"write", timings.write}}},
  };
  backend.write_stats(stats);
  return stats;
}

}  // namespace kinray
