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

#include "renderer/image_io.h"
#include "renderer/render_job.h"
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

  RenderParams params;
  params.scene = c.scene;
  if (c.root != ModelRoot::kNone) {
    const fs::path path = fs::path(c.root == ModelRoot::kShared ? config.shared_models : config.test_models) / c.scene;
    std::error_code error;
    if (!fs::is_regular_file(path, error)) {
      result.message = path.string() + " is not installed";
      return finish(RegressionStatus::kSkipped);
    }
    params.scene = path.string();
  }
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

  std::unique_ptr<RenderJob> job;
  try {
    job = std::make_unique<RenderJob>(params);
  } catch (const std::exception& e) {
    general.push_back(std::string("cannot load the scene: ") + e.what());
    return finish(RegressionStatus::kFailed);
  }
  const Json expected = manifest(c, *job);
  const fs::path references = fs::path(config.references) / c.name;
  if (!config.update) {
    const fs::path stored = references / "case.json";
    std::error_code error;
    if (!fs::is_regular_file(stored, error)) {
      general.push_back("no references in " + references.string() +
                        " (record them deliberately: kinray regress --update-references --case " + c.name + ")");
      return finish(RegressionStatus::kFailed);
    }
    try {
      const std::string difference = manifest_difference(read_json_file(stored), expected);
      if (!difference.empty()) {
        general.push_back("the references in " + references.string() + " were made for another version of the case: " +
                          difference + " (if the change is deliberate: kinray regress --update-references --case " +
                          c.name + ")");
        return finish(RegressionStatus::kFailed);
      }
    } catch (const InputError& e) {
      general.push_back(e.what());
      return finish(RegressionStatus::kFailed);
    }
  }

  fs::path report;
  if (!config.report.empty()) {
    report = fs::path(config.report) / c.name;
    std::error_code error;
    fs::remove_all(report, error);  // only this case's folder: no stale images of an earlier run
  }
  auto report_file = [&](const std::string& name) {
    fs::create_directories(report);
    result.report_folder = report.string();
    return (report / name).string();
  };

  std::unique_ptr<Backend> kinetic, embree;
  try {
    kinetic = job->make_backend("kinetic");
    embree = job->make_backend("embree");
  } catch (const std::exception& e) {
    general.push_back(std::string("cannot create the backends: ") + e.what());
    return finish(RegressionStatus::kFailed);
  }
  FrameComparator comparator(job->camera_space(), config.tolerance);
  std::vector<Frame> rendered;  // kept for an update, which writes only once every frame passed
  Frame a, b, stored;
  for (size_t f = 0; f < job->frame_times().size(); ++f) {
    RegressionFrameResult line;
    line.frame = f;
    line.time = job->frame_times()[f];
    try {
      job->render_frame(*kinetic, f, a);
    } catch (const std::exception& e) {
      // An audit violation (std::logic_error) or any other failure of the kinetic backend.
      line.problems.push_back(std::string("the kinetic backend failed: ") + e.what());
      result.frames.push_back(std::move(line));
      break;
    }
    job->render_frame(*embree, f, b);
    line.covered = size_t(std::count_if(a.object.begin(), a.object.end(), [](uint32_t o) { return o != kNoHit; }));
    const FrameDiff against_embree = comparator.compare(a, b);
    line.embree_real = against_embree.mismatch_real;
    line.embree_ties = against_embree.mismatch_tie;
    if (line.embree_real > 0)
      line.problems.push_back(std::to_string(line.embree_real) + " real mismatches against Embree (" +
                              std::to_string(against_embree.cracks) + " cracks)");

    std::optional<FrameDiff> against_reference;
    cv::Mat reference_bgr;
    const cv::Mat tested_bgr = color_image(a);
    if (!config.update) {
      try {
        stored.resize(c.width, c.height);
        read_id_png((references / numbered("id", f)).string(), stored);
        reference_bgr = read_color_png((references / numbered("color", f)).string());
        if (stored.width != c.width || stored.height != c.height || reference_bgr.cols != c.width ||
            reference_bgr.rows != c.height)
          throw InputError(references.string(), "reference frame " + std::to_string(f) + " is not " +
                                                    std::to_string(c.width) + "x" + std::to_string(c.height));
        stored.time = line.time;
        set_colors(reference_bgr, stored);
        against_reference = comparator.compare(a, stored);
        line.reference_real = against_reference->mismatch_real;
        line.reference_ties = against_reference->mismatch_tie;
        if (line.reference_real > 0)
          line.problems.push_back(std::to_string(line.reference_real) + " real mismatches against the reference " +
                                  (references / numbered("id", f)).string());
        const CodeError colors = compare_codes(tested_bgr, reference_bgr, *against_reference);
        line.psnr_db = colors.psnr_db;
        line.max_code_error = colors.max_on_agreeing;
        if (line.max_code_error > config.color.max_code_error)
          line.problems.push_back("shaded colour differs from " + (references / numbered("color", f)).string() + " by " +
                                  std::to_string(line.max_code_error) + " codes where the triangles agree (allowed: " +
                                  std::to_string(config.color.max_code_error) + ")");
        if (line.psnr_db && *line.psnr_db < config.color.min_psnr_db) {
          char text[160];
          std::snprintf(text, sizeof text, "shaded PSNR %.2f dB against the reference is below %.1f dB", *line.psnr_db,
                        config.color.min_psnr_db);
          line.problems.push_back(text);
        }
      } catch (const InputError& e) {
        line.problems.push_back(std::string("cannot read the reference: ") + e.what());
      }
    }

    if (!line.passed() && !report.empty()) {
      try {
        write_color_png(report_file(numbered("kinetic", f)), a);
        write_id_png(report_file(numbered("kinetic_id", f)), a);
        write_color_png(report_file(numbered("embree", f)), b);
        write_heat_map(against_embree, report_file(numbered("embree_diff", f)), &b);
        if (against_reference) {
          write_image(report_file(numbered("reference", f)), reference_bgr);
          write_heat_map(*against_reference, report_file(numbered("reference_diff", f)), &stored);
          write_color_error(report_file(numbered("color_error", f)), tested_bgr, reference_bgr);
        }
      } catch (const std::exception& e) {
        line.problems.push_back(std::string("cannot write the report: ") + e.what());
      }
    }
    if (config.update) rendered.push_back(a);
    result.frames.push_back(std::move(line));
  }

  const bool all_passed = std::all_of(result.frames.begin(), result.frames.end(),
                                      [](const RegressionFrameResult& f) { return f.passed(); }) &&
                          result.frames.size() == job->frame_times().size();
  if (!all_passed) {
    if (config.update) general.push_back("references not updated: the kinetic frames must agree with Embree first");
    return finish(RegressionStatus::kFailed);
  }
  if (!config.update) return finish(RegressionStatus::kPassed);

  std::error_code error;
  fs::create_directories(references, error);
  if (error) {
    general.push_back("cannot create " + references.string() + ": " + error.message());
    return finish(RegressionStatus::kFailed);
  }
  try {
    for (size_t f = 0; f < rendered.size(); ++f) {
      write_id_png((references / numbered("id", f)).string(), rendered[f]);
      write_color_png((references / numbered("color", f)).string(), rendered[f]);
    }
    remove_stale_frames(references, rendered.size());
    write_file_atomically((references / "case.json").string(), expected.dump(2) + "\n");
  } catch (const std::exception& e) {
    general.push_back(std::string("cannot write the references: ") + e.what());
    return finish(RegressionStatus::kFailed);
  }
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
