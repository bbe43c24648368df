#include "verification/regression_suite.h"

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <fstream>
#include <memory>
#include <ostream>
#include <sstream>
#include <system_error>

#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>

#include "renderer/output/image_io.h"
#include "renderer/job/render_job.h"
#include "scenes/texture_image.h"
#include "util/input_error.h"

namespace kinray {
namespace {

namespace fs = std::filesystem;
using Json = nlohmann::json;

// Small images, few triangles and short shots: the whole suite runs in seconds with the audit on,
// and its references stay a few kilobytes per frame. The built-ins are cut to one second with
// eight keys, so each case still crosses keyframes between its frames; the models keep their
// own shot and keys. The frame times (0, 1/3, 2/3, 1 of the shot) fall between keys.
RegressionCase builtin(const char* name, const char* spec) {
  RegressionCase c;
  c.name = name;
  c.scene = spec;
  return c;
}

RegressionCase model(const char* name, const char* path, ModelRoot root) {
  RegressionCase c;
  c.name = name;
  c.scene = path;
  c.root = root;
  return c;
}

const std::vector<RegressionCase> kCases = {
    builtin("wavy-sphere", "wavy-sphere:triangles=1000,duration=1,keyrate=8"),
    builtin("cloth", "cloth:triangles=1000,duration=1,keyrate=8"),
    builtin("orbit", "orbit:triangles=1000,duration=1,keyrate=8"),
    builtin("flythrough", "flythrough:triangles=500,duration=1,keyrate=8"),
    // The box is visible on [1/3, 0.75): the frame at 1/3 sees it appear.
    builtin("static-moving", "static-moving:triangles=1000,duration=1,keyrate=8"),
    // Skinned DirectX (its first animation, Wuson_Run), skinned glTF, glTF morph targets (the
    // shared folder's sphere and the sample cube), COLLADA node animation, and an FBX skeleton
    // seen through the model's own camera.
    model("x-testwuson", "X/Testwuson.X", ModelRoot::kTestModels),
    model("gltf-simple-skin", "glTF2/simple_skin/simple_skin.gltf", ModelRoot::kTestModels),
    model("gltf-morph-sphere", "glTF2/AnimatedMorphSphere/glTF/AnimatedMorphSphere.gltf", ModelRoot::kShared),
    model("gltf-morph-cube", "glTF2/glTF-Sample-Models/AnimatedMorphCube-glTF/AnimatedMorphCube.gltf",
          ModelRoot::kTestModels),
    model("dae-box-nested", "Collada/box_nested_animation.dae", ModelRoot::kTestModels),
    model("fbx-huesitos", "FBX/huesitos.fbx", ModelRoot::kTestModels),
};

const char* root_name(ModelRoot root) {
  switch (root) {
    case ModelRoot::kNone: return "builtin";
    case ModelRoot::kTestModels: return "assimp-testmodels";
    case ModelRoot::kShared: return "shared";
  }
  return "?";
}

std::string numbered(const char* prefix, size_t index) {
  char name[64];
  std::snprintf(name, sizeof name, "%s_%05zu.png", prefix, index);
  return name;
}

std::string format_time(double t) {
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", t);
  return text;
}

/// The shaded colours of an 8-bit sRGB image (BGR), as a frame's linear colour: what the heat
/// maps draw in dim grey under the mismatches.
void set_colors(const cv::Mat& bgr, Frame& frame) {
  for (int j = 0; j < frame.height && j < bgr.rows; ++j)
    for (int i = 0; i < frame.width && i < bgr.cols; ++i) {
      const cv::Vec3b& c = bgr.at<cv::Vec3b>(j, i);
      frame.color[frame.index(i, j)] = Color(srgb_to_linear(c[2]), srgb_to_linear(c[1]), srgb_to_linear(c[0]));
    }
}

/// Shaded comparison in 8-bit sRGB codes: PSNR over the whole frame, largest channel error where
/// the ID comparison found the same triangle (or background) on both sides.
struct CodeError {
  std::optional<double> psnr_db;
  int max_on_agreeing = 0;
};

CodeError compare_codes(const cv::Mat& tested, const cv::Mat& reference, const FrameDiff& ids) {
  CodeError error;
  double squares = 0;
  for (int j = 0; j < tested.rows; ++j)
    for (int i = 0; i < tested.cols; ++i) {
      const cv::Vec3b& a = tested.at<cv::Vec3b>(j, i);
      const cv::Vec3b& b = reference.at<cv::Vec3b>(j, i);
      int largest = 0;
      for (int c = 0; c < 3; ++c) {
        const int d = std::abs(int(a[c]) - int(b[c]));
        squares += double(d) * d;
        largest = std::max(largest, d);
      }
      const PixelClass k = ids.pixels[size_t(j) * size_t(tested.cols) + size_t(i)];
      if (k == PixelClass::kEqual || k == PixelClass::kBackground)
        error.max_on_agreeing = std::max(error.max_on_agreeing, largest);
    }
  if (squares > 0) {
    const double mse = squares / (3.0 * double(tested.total()));
    error.psnr_db = 10 * std::log10(255.0 * 255.0 / mse);
  }
  return error;
}

/// |tested - reference| per pixel (largest channel), times 8 so that one code shows.
void write_color_error(const std::string& path, const cv::Mat& tested, const cv::Mat& reference) {
  cv::Mat image(tested.rows, tested.cols, CV_8UC1);
  for (int j = 0; j < tested.rows; ++j)
    for (int i = 0; i < tested.cols; ++i) {
      int largest = 0;
      for (int c = 0; c < 3; ++c)
        largest = std::max(largest, std::abs(int(tested.at<cv::Vec3b>(j, i)[c]) - int(reference.at<cv::Vec3b>(j, i)[c])));
      image.at<uint8_t>(j, i) = uint8_t(std::min(255, 8 * largest));
    }
  write_image(path, image);
}

Json read_json_file(const fs::path& path) {
  std::ifstream file(path);
  if (!file) throw InputError(path.string(), "cannot be read");
  try {
    return Json::parse(file);
  } catch (const Json::exception& e) {
    throw InputError(path.string(), std::string("not valid JSON: ") + e.what());
  }
}

/// What the references of a case were rendered from, so that a changed case (other scene, size
/// or frame times) is reported as stale references instead of as a thousand mismatched pixels.
Json manifest(const RegressionCase& c, const RenderJob& job) {
  Json frames = Json::array();
  for (size_t f = 0; f < job.frame_times().size(); ++f)
    frames.push_back({{"time", job.frame_times()[f]}, {"id", numbered("id", f)}, {"color", numbered("color", f)}});
  return {{"case", c.name},
          {"scene", c.scene},
          {"root", root_name(c.root)},
          {"animation", c.animation},
          {"size", {c.width, c.height}},
          {"backend", "kinetic"},
          {"triangles", job.scene().triangle_count()},
          {"frame_times", job.frame_times()},
          {"frames", frames}};
}

/// Empty when the stored manifest describes the same renders as `expected`; else what differs.
std::string manifest_difference(const Json& stored, const Json& expected) {
  for (const char* key : {"scene", "root", "animation", "size", "triangles"})
    if (!stored.contains(key) || stored[key] != expected[key])
      return std::string("'") + key + "' is " + (stored.contains(key) ? stored[key].dump() : "missing") + ", the case has " +
             expected[key].dump();
  const auto& times = expected["frame_times"];
  if (!stored.contains("frame_times") || !stored["frame_times"].is_array() || stored["frame_times"].size() != times.size())
    return "the references have " + (stored.contains("frame_times") ? std::to_string(stored["frame_times"].size()) : "no") +
           " frame times, the case has " + std::to_string(times.size());
  for (size_t f = 0; f < times.size(); ++f) {
    // Frame times come from the model's shot; allow for a printed-and-parsed last digit only.
    const double a = stored["frame_times"][f].get<double>(), b = times[f].get<double>();
    if (std::abs(a - b) > 1e-12 * std::max(1.0, std::abs(b)))
      return "frame " + std::to_string(f) + " is at t = " + format_time(a) + " in the references, " + format_time(b) +
             " in the case";
  }
  return "";
}

/// Removes the frame files of an earlier, longer set of references.
void remove_stale_frames(const fs::path& folder, size_t frames) {
  std::error_code error;
  for (const auto& entry : fs::directory_iterator(folder, error)) {
    const std::string name = entry.path().filename().string();
    for (const char* prefix : {"id_", "color_"}) {
      const std::string p = prefix;
      if (name.rfind(p, 0) != 0 || entry.path().extension() != ".png") continue;
      const std::string digits = name.substr(p.size(), name.size() - p.size() - 4);
      if (digits.empty() || !std::all_of(digits.begin(), digits.end(), [](unsigned char d) { return std::isdigit(d); }))
        continue;
      if (std::stoul(digits) >= frames) fs::remove(entry.path(), error);
    }
  }
}

std::string join_problems(const std::vector<RegressionFrameResult>& frames, const std::vector<std::string>& general) {
  std::vector<std::string> lines = general;
  for (const RegressionFrameResult& f : frames)
    for (const std::string& p : f.problems)
      lines.push_back("frame " + std::to_string(f.frame) + " (t = " + format_time(f.time) + "): " + p);
  std::string text;
  for (const std::string& line : lines) {
    if (!text.empty()) text.push_back('\n');
    text.append(line);
  }
  return text;
}

/// Where a case's model file is installed; empty for a built-in scene.
fs::path model_path(const RegressionCase& c, const RegressionConfig& config) {
  if (c.root == ModelRoot::kNone) return {};
  return fs::path(c.root == ModelRoot::kShared ? config.shared_models : config.test_models) / c.scene;
}

/// The render of a case: the kinetic backend, audited as configured, quiet.
RenderParams case_render_params(const RegressionCase& c, const RegressionConfig& config, const fs::path& model) {
  RenderParams params;
  params.scene = model.empty() ? c.scene : model.string();
  params.backend = "kinetic";
  params.width = c.width;
  params.height = c.height;
  params.frames = c.frames;
  params.time = c.time;
  params.animation = c.animation;
  params.audit = config.audit;
  // Models may bring lights; the cases are tiny, so their shadow rays are traced by brute force.
  params.shadow_tree = ShadowTree::brute;
  params.threads = config.threads;
  params.quiet = true;
  return params;
}

/// Checks the stored manifest in `references` against the case: empty when the references were
/// made for it, else the problem.
std::string check_stored_manifest(const RegressionCase& c, const fs::path& references, const Json& expected) {
  const fs::path stored = references / "case.json";
  std::error_code error;
  if (!fs::is_regular_file(stored, error))
    return "no references in " + references.string() +
           " (record them deliberately: kinray regress --update-references --case " + c.name + ")";
  try {
    const std::string difference = manifest_difference(read_json_file(stored), expected);
    if (!difference.empty())
      return "the references in " + references.string() + " were made for another version of the case: " +
             difference + " (if the change is deliberate: kinray regress --update-references --case " + c.name + ")";
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

/// A case's report folder, emptied of an earlier run; empty when no report is configured.
fs::path clear_report_folder(const RegressionCase& c, const RegressionConfig& config) {
  if (config.report.empty()) return {};
  const fs::path report = fs::path(config.report) / c.name;
  std::error_code error;
  fs::remove_all(report, error);  // only this case's folder: no stale images of an earlier run
  return report;
}

/// What every frame of a case is rendered with, compared with and reported to.
struct CaseFrames {
  const RegressionCase& c;
  const RegressionConfig& config;
  RenderJob& job;
  Backend& kinetic;
  Backend& embree;
  FrameComparator& comparator;
  const fs::path& references;
};

/// One frame's images and comparisons, kept for its failure report. The frames are reused
/// from one frame of a case to the next.
struct FrameImages {
  Frame kinetic, embree, reference;
  FrameDiff against_embree;
  std::optional<FrameDiff> against_reference;
  cv::Mat tested_bgr, reference_bgr;
};

/// Compares the kinetic frame `f` against its stored reference: triangle IDs, then the shaded
/// colours; adds the problems to `line`.
void compare_with_reference(const CaseFrames& cf, size_t f, FrameImages& images, RegressionFrameResult& line) {
  const RegressionCase& c = cf.c;
  const ColorThresholds& color = cf.config.color;
  try {
    images.reference.resize(c.width, c.height);
    read_id_png((cf.references / numbered("id", f)).string(), images.reference);
    images.reference_bgr = read_color_png((cf.references / numbered("color", f)).string());
    if (images.reference.width != c.width || images.reference.height != c.height ||
        images.reference_bgr.cols != c.width || images.reference_bgr.rows != c.height)
      throw InputError(cf.references.string(), "reference frame " + std::to_string(f) + " is not " +
                                                   std::to_string(c.width) + "x" + std::to_string(c.height));
    images.reference.time = line.time;
    set_colors(images.reference_bgr, images.reference);
    images.against_reference = cf.comparator.compare(images.kinetic, images.reference);
    line.reference_real = images.against_reference->mismatch_real;
    line.reference_ties = images.against_reference->mismatch_tie;
    if (line.reference_real > 0)
      line.problems.push_back(std::to_string(line.reference_real) + " real mismatches against the reference " +
                              (cf.references / numbered("id", f)).string());
    const CodeError colors = compare_codes(images.tested_bgr, images.reference_bgr, *images.against_reference);
    line.psnr_db = colors.psnr_db;
    line.max_code_error = colors.max_on_agreeing;
    if (line.max_code_error > color.max_code_error)
      line.problems.push_back("shaded colour differs from " + (cf.references / numbered("color", f)).string() + " by " +
                              std::to_string(line.max_code_error) + " codes where the triangles agree (allowed: " +
                              std::to_string(color.max_code_error) + ")");
    if (line.psnr_db && *line.psnr_db < color.min_psnr_db) {
      char text[160];
      std::snprintf(text, sizeof text, "shaded PSNR %.2f dB against the reference is below %.1f dB", *line.psnr_db,
                    color.min_psnr_db);
      line.problems.push_back(text);
    }
  } catch (const InputError& e) {
    line.problems.push_back(std::string("cannot read the reference: ") + e.what());
  }
}

/// Renders frame `f` with both backends and compares the kinetic frame against Embree and, unless
/// updating, against the reference. False when the kinetic backend failed (the case stops there).
bool compare_frame(const CaseFrames& cf, size_t f, FrameImages& images, RegressionFrameResult& line) {
  try {
    cf.job.render_frame(cf.kinetic, f, images.kinetic);
  } catch (const std::exception& e) {
    // An audit violation (std::logic_error) or any other failure of the kinetic backend.
    line.problems.push_back(std::string("the kinetic backend failed: ") + e.what());
    return false;
  }
  const Frame& a = images.kinetic;
  cf.job.render_frame(cf.embree, f, images.embree);
  line.covered = size_t(std::count_if(a.object.begin(), a.object.end(), [](uint32_t o) { return o != kNoHit; }));
  images.against_embree = cf.comparator.compare(a, images.embree);
  line.embree_real = images.against_embree.mismatch_real;
  line.embree_ties = images.against_embree.mismatch_tie;
  if (line.embree_real > 0)
    line.problems.push_back(std::to_string(line.embree_real) + " real mismatches against Embree (" +
                            std::to_string(images.against_embree.cracks) + " cracks)");

  images.against_reference.reset();
  images.reference_bgr = cv::Mat();
  images.tested_bgr = color_image(a);
  if (!cf.config.update) compare_with_reference(cf, f, images, line);
  return true;
}

/// Writes the images of failed frame `f` into `report`, created on first use and then named in
/// `report_folder`; a write failure is one more problem of the frame.
void write_frame_report(const fs::path& report, size_t f, const FrameImages& images, std::string& report_folder,
                        RegressionFrameResult& line) {
  auto report_file = [&](const std::string& name) {
    fs::create_directories(report);
    report_folder = report.string();
    return (report / name).string();
  };
  try {
    write_color_png(report_file(numbered("kinetic", f)), images.kinetic);
    write_id_png(report_file(numbered("kinetic_id", f)), images.kinetic);
    write_color_png(report_file(numbered("embree", f)), images.embree);
    write_heat_map(images.against_embree, report_file(numbered("embree_diff", f)), &images.embree);
    if (images.against_reference) {
      write_image(report_file(numbered("reference", f)), images.reference_bgr);
      write_heat_map(*images.against_reference, report_file(numbered("reference_diff", f)), &images.reference);
      write_color_error(report_file(numbered("color_error", f)), images.tested_bgr, images.reference_bgr);
    }
  } catch (const std::exception& e) {
    line.problems.push_back(std::string("cannot write the report: ") + e.what());
  }
}

/// Compares every frame of the case into `result.frames` until the kinetic backend fails, writing
/// the report of each failed frame; keeps the kinetic frames in `rendered` when updating.
void compare_frames(const CaseFrames& cf, const fs::path& report, RegressionCaseResult& result,
                    std::vector<Frame>& rendered) {
  FrameImages images;
  for (size_t f = 0; f < cf.job.frame_times().size(); ++f) {
    RegressionFrameResult line;
    line.frame = f;
    line.time = cf.job.frame_times()[f];
    if (!compare_frame(cf, f, images, line)) {
      result.frames.push_back(std::move(line));
      break;
    }
    if (!line.passed() && !report.empty()) write_frame_report(report, f, images, result.report_folder, line);
    if (cf.config.update) rendered.push_back(images.kinetic);
    result.frames.push_back(std::move(line));
  }
}

/// Writes the rendered frames and the manifest as the case's references: empty when written,
/// else the problem.
std::string write_references(const fs::path& references, const std::vector<Frame>& rendered, const Json& expected) {
  std::error_code error;
  fs::create_directories(references, error);
  if (error) return "cannot create " + references.string() + ": " + error.message();
  try {
    for (size_t f = 0; f < rendered.size(); ++f) {
      write_id_png((references / numbered("id", f)).string(), rendered[f]);
      write_color_png((references / numbered("color", f)).string(), rendered[f]);
    }
    remove_stale_frames(references, rendered.size());
    write_file_atomically((references / "case.json").string(), expected.dump(2) + "\n");
  } catch (const std::exception& e) {
    return std::string("cannot write the references: ") + e.what();
  }
  return "";
}

}  // namespace

const std::vector<RegressionCase>& regression_cases() { return kCases; }

const RegressionCase& find_regression_case(const std::string& name) {
  for (const RegressionCase& c : kCases)
    if (c.name == name) return c;
  std::string names;
  for (const RegressionCase& c : kCases) names += (names.empty() ? "" : ", ") + c.name;
  throw InputError("--case", "no case '" + name + "' (cases: " + names + ")");
}

const char* status_name(RegressionStatus status) {
  switch (status) {
    case RegressionStatus::kPassed: return "passed";
    case RegressionStatus::kFailed: return "FAILED";
    case RegressionStatus::kUpdated: return "updated";
    case RegressionStatus::kSkipped: return "skipped";
  }
  return "?";
}

RegressionCaseResult run_regression_case(const RegressionCase& c, const RegressionConfig& config) {
  const auto started = std::chrono::steady_clock::now();
  RegressionCaseResult result;
  result.name = c.name;
  std::vector<std::string> general;  // problems that belong to no frame
  auto finish = [&](RegressionStatus status) {
    result.status = status;
    if (status == RegressionStatus::kFailed) {
      result.message = join_problems(result.frames, general);
      if (!result.report_folder.empty()) result.message += "\nreport: " + result.report_folder;
    }
    result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    return result;
  };
  auto fail = [&](std::string problem) {
    general.push_back(std::move(problem));
    return finish(RegressionStatus::kFailed);
  };

  const fs::path model = model_path(c, config);
  std::error_code error;
  if (!model.empty() && !fs::is_regular_file(model, error)) {
    result.message = model.string() + " is not installed";
    return finish(RegressionStatus::kSkipped);
  }
  std::unique_ptr<RenderJob> job;
  try {
    job = std::make_unique<RenderJob>(case_render_params(c, config, model));
  } catch (const std::exception& e) {
    return fail(std::string("cannot load the scene: ") + e.what());
  }
  const Json expected = manifest(c, *job);
  const fs::path references = fs::path(config.references) / c.name;
  if (!config.update) {
    const std::string problem = check_stored_manifest(c, references, expected);
    if (!problem.empty()) return fail(problem);
  }
  const fs::path report = clear_report_folder(c, config);

  std::unique_ptr<Backend> kinetic, embree;
  try {
    kinetic = job->make_backend("kinetic");
    embree = job->make_backend("embree");
  } catch (const std::exception& e) {
    return fail(std::string("cannot create the backends: ") + e.what());
  }
  FrameComparator comparator(job->camera_space(), config.tolerance);
  std::vector<Frame> rendered;  // kept for an update, which writes only once every frame passed
  compare_frames({c, config, *job, *kinetic, *embree, comparator, references}, report, result, rendered);

  const bool all_passed = std::all_of(result.frames.begin(), result.frames.end(),
                                      [](const RegressionFrameResult& f) { return f.passed(); }) &&
                          result.frames.size() == job->frame_times().size();
  if (!all_passed) {
    if (config.update) general.push_back("references not updated: the kinetic frames must agree with Embree first");
    return finish(RegressionStatus::kFailed);
  }
  if (!config.update) return finish(RegressionStatus::kPassed);
  const std::string problem = write_references(references, rendered, expected);
  if (!problem.empty()) return fail(problem);
  return finish(RegressionStatus::kUpdated);
}

void print_regression_header(std::ostream& out) {
  char text[200];
  std::snprintf(text, sizeof text, "%-20s %-8s %6s %9s %9s %9s %8s %11s %11s %8s\n", "case", "result", "frames",
                "ref_real", "ref_ties", "psnr_dB", "max_err", "embree_real", "embree_ties", "seconds");
  out << text;
}

void print_regression_line(std::ostream& out, const RegressionCaseResult& r) {
  size_t ref_real = 0, ref_ties = 0, embree_real = 0, embree_ties = 0;
  std::optional<double> psnr;
  int max_error = 0;
  for (const RegressionFrameResult& f : r.frames) {
    ref_real += f.reference_real;
    ref_ties += f.reference_ties;
    embree_real += f.embree_real;
    embree_ties += f.embree_ties;
    max_error = std::max(max_error, f.max_code_error);
    if (f.psnr_db) psnr = psnr ? std::min(*psnr, *f.psnr_db) : *f.psnr_db;
  }
  char psnr_text[32];
  if (psnr)
    std::snprintf(psnr_text, sizeof psnr_text, "%.2f", *psnr);
  else
    std::snprintf(psnr_text, sizeof psnr_text, "%s", r.status == RegressionStatus::kUpdated ? "-" : "inf");
  char text[256];
  std::snprintf(text, sizeof text, "%-20s %-8s %6zu %9zu %9zu %9s %8d %11zu %11zu %8.2f\n", r.name.c_str(),
                status_name(r.status), r.frames.size(), ref_real, ref_ties, psnr_text, max_error, embree_real,
                embree_ties, r.seconds);
  out << text;
  if (!r.message.empty()) {
    std::istringstream lines(r.message);
    for (std::string line; std::getline(lines, line);) out << "    " << line << "\n";
  }
}

}  // namespace kinray
