// kinray info SCENE: what a scene holds (triangles, vertices, objects, keyframes, duration, bounds,
// camera keys), as text or --json.
#include <cmath>
#include <cstdio>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "scenes/mesh_sequence.h"
#include "scenes/scene_loader.h"
#include "tools/cli/camera_flags.h"
#include "tools/cli_options.h"
#include "tools/commands.h"
#include "util/input_error.h"

namespace kinray {
namespace {

struct InfoOptions {
  std::string scene;
  std::string animation;
  double keyrate = 0;
  CameraParams camera;
  bool json = false;
};

constexpr size_t kListedObjects = 20;

nlohmann::json vec(const Vec3& v) {
  return {v.x(), v.y(), v.z()};
}

std::string text(const Vec3& v) {
  std::ostringstream out;
  out << "(" << v.x() << ", " << v.y() << ", " << v.z() << ")";
  return out.str();
}

nlohmann::json describe_camera_source(const CameraSource& source) {
  nlohmann::json json = {{"kind", kind_name(source.kind)}};
  if (!source.name.empty()) json["name"] = source.name;
  if (!source.reason.empty()) json["reason"] = source.reason;
  return json;
}

nlohmann::json describe_animations(const ModelCatalog& catalog) {
  nlohmann::json animations = nlohmann::json::array();
  for (const AnimationSummary& animation : catalog.animations)
    animations.push_back({{"index", animation.index},
                          {"name", animation.name},
                          {"duration", animation.duration()},
                          {"first_key", animation.first_key},
                          {"last_key", animation.last_key},
                          {"ticks_per_second", animation.ticks_per_second},
                          {"assimp_duration", animation.assimp_duration},
                          {"node_channels", animation.node_channels},
                          {"morph_channels", animation.morph_channels},
                          {"mesh_channels", animation.mesh_channels},
                          {"default", animation.index == 0},
                          {"played", animation.index == catalog.played}});
  return animations;
}

nlohmann::json describe(const std::string& spec, const Scene& scene) {
  const Eigen::AlignedBox3d bounds = scene.bounds();
  size_t moving = 0;
  nlohmann::json objects = nlohmann::json::array();
  for (const Object& object : scene.objects) {
    const bool is_static = object.is_static();
    moving += !is_static;
    nlohmann::json entry = {{"name", object.name},
                            {"triangles", object.triangles.size()},
                            {"vertices", object.vertex_count()},
                            {"keys", object.key_count()},
                            {"static", is_static},
                            {"material", object.material}};
    if (std::isfinite(object.appear)) entry["appear"] = object.appear;
    if (std::isfinite(object.disappear)) entry["disappear"] = object.disappear;
    objects.push_back(entry);
  }
  nlohmann::json camera = nlohmann::json::array();
  for (const CameraKey& key : scene.camera.keys) {
    const Eigen::Matrix3d rotation = key.orientation.normalized().toRotationMatrix();
    camera.push_back({{"time", key.time},
                      {"position", vec(key.position)},
                      {"direction", vec(rotation * Vec3(0, 0, -1))},
                      {"up", vec(rotation * Vec3(0, 1, 0))},
                      {"fov_y_degrees", key.fov_y_degrees}});
  }
  nlohmann::json lights = nlohmann::json::array();
  for (const Light& light : scene.lights) {
    const bool point = light.kind == Light::Kind::point;
    lights.push_back(
        {{"kind", point ? "point" : "directional"},
         {point ? "position" : "direction", vec(point ? light.position : light.direction)},
         {"color", {light.color.x(), light.color.y(), light.color.z()}}});
  }
  const std::vector<double> key_times = scene.key_times();
  return {{"scene", spec},
          {"name", scene.name},
          {"triangles", scene.triangle_count()},
          {"vertices", scene.vertex_count()},
          {"objects", scene.objects.size()},
          {"moving_objects", moving},
          {"materials", scene.materials.size()},
          {"textures", scene.textures.size()},
          {"keyframes", key_times.size()},
          {"key_times", key_times},
          {"time_begin", scene.time_begin},
          {"time_end", scene.time_end},
          {"duration", scene.time_end - scene.time_begin},
          {"bounds", bounds.isEmpty()
                         ? nlohmann::json(nullptr)
                         : nlohmann::json{{"min", vec(bounds.min())}, {"max", vec(bounds.max())}}},
          {"camera_source", describe_camera_source(scene.camera_source)},
          {"camera_keys", camera},
          {"lights", lights},
          {"object_list", objects}};
}

/// A mesh sequence: its frame count (one key per file), key rate and first and last files.
nlohmann::json describe_sequence(const std::string& spec, const Scene& scene) {
  const std::vector<std::string> files = mesh_sequence_files(spec);
  const Object& object = scene.objects.front();
  const double keyrate = object.key_count() > 1 ? 1 / (object.key_times[1] - object.key_times[0])
                                                : 1 / (scene.time_end - scene.time_begin);
  return {{"frames", files.size()}, {"keyrate", keyrate}, {"first", files.front()}, {"last", files.back()}};
}

/// Where the camera comes from, then its keys (the first kListedObjects).
void print_camera(const Scene& scene, const nlohmann::json& info) {
  const CameraSource& source = scene.camera_source;
  std::string origin;
  switch (source.kind) {
    case CameraSource::Kind::scene:
      origin = "the scene's own";
      break;
    case CameraSource::Kind::model:
      origin = "the model's own camera '" + source.name + "'";
      break;
    case CameraSource::Kind::automatic:
      origin = std::string("automatic framing, ") +
               (scene.camera.keys.size() > 1 ? "following the subject" : "still") + " (" +
               source.reason + ")";
      break;
    case CameraSource::Kind::command_line:
      origin = "from the command line (--eye, --target)";
      break;
  }
  std::printf("camera      %s; %zu key%s\n", origin.c_str(), scene.camera.keys.size(),
              scene.camera.keys.size() == 1 ? "" : "s");
  size_t listed = 0;
  for (const auto& key : info["camera_keys"]) {
    if (listed++ == kListedObjects) {
      std::printf("  ... and %zu more keys\n", scene.camera.keys.size() - kListedObjects);
      break;
    }
    const auto p = key["position"], d = key["direction"];
    std::printf("  t=%-8g position (%g, %g, %g)  looking (%g, %g, %g)  fov_y %g deg\n",
                key["time"].get<double>(), p[0].get<double>(), p[1].get<double>(),
                p[2].get<double>(), d[0].get<double>(), d[1].get<double>(), d[2].get<double>(),
                key["fov_y_degrees"].get<double>());
  }
}

/// A model's animations, one line each, marking the one render plays by default and the one shown.
void print_animations(const nlohmann::json& info) {
  if (!info.contains("animations")) return;
  const nlohmann::json& animations = info["animations"];
  if (animations.empty()) {
    std::printf("animations  none (the model is shown still)\n");
    return;
  }
  std::printf(
      "animations  %zu (render plays %s by default; --animation NAME|INDEX picks another)\n",
      animations.size(), animations[0]["index"].dump().c_str());
  for (const auto& animation : animations) {
    const auto count = [&](const char* key, const std::string& what) {
      const size_t n = animation[key].get<size_t>();
      return std::to_string(n) + " " + what + (n == 1 ? "" : "s");
    };
    std::string channels = count("node_channels", "node channel");
    if (animation["morph_channels"].get<size_t>() > 0)
      channels += ", " + count("morph_channels", "morph channel");
    if (animation["mesh_channels"].get<size_t>() > 0)
      channels += ", " + count("mesh_channels", "vertex channel") + " (ignored)";
    std::string marks;
    if (animation["default"].get<bool>()) marks += "  default";
    if (animation["played"].get<bool>()) marks += "  shown here";
    std::printf("  %-3zu %-24s %8g s  (keys %g..%g s)  %s%s\n", animation["index"].get<size_t>(),
                ("'" + animation["name"].get<std::string>() + "'").c_str(),
                animation["duration"].get<double>(), animation["first_key"].get<double>(),
                animation["last_key"].get<double>(), channels.c_str(), marks.c_str());
  }
}

void print_text(const Scene& scene, const nlohmann::json& info) {
  std::printf("scene       %s (%s)\n", info["scene"].get<std::string>().c_str(),
              scene.name.c_str());
  std::printf("triangles   %zu\n", scene.triangle_count());
  std::printf("vertices    %zu\n", scene.vertex_count());
  std::printf("objects     %zu (%zu moving, %zu static)\n", scene.objects.size(),
              info["moving_objects"].get<size_t>(),
              scene.objects.size() - info["moving_objects"].get<size_t>());
  std::printf("materials   %zu (%zu textures)\n", scene.materials.size(), scene.textures.size());
  if (info.contains("sequence")) {
    const nlohmann::json& sequence = info["sequence"];
    std::printf("sequence    mesh sequence with %zu frames (one file per key, %g keys/s): %s .. %s\n",
                sequence["frames"].get<size_t>(), sequence["keyrate"].get<double>(),
                sequence["first"].get<std::string>().c_str(),
                sequence["last"].get<std::string>().c_str());
  }
  std::printf("keyframes   %zu (the key grid that --inbetweens subdivides)\n",
              info["keyframes"].get<size_t>());
  std::printf("duration    %g s (shot [%g, %g])\n", scene.time_end - scene.time_begin,
              scene.time_begin, scene.time_end);
  const Eigen::AlignedBox3d bounds = scene.bounds();
  if (bounds.isEmpty())
    std::printf("bounds      empty\n");
  else
    std::printf("bounds      min %s  max %s\n", text(bounds.min()).c_str(),
                text(bounds.max()).c_str());
  print_animations(info);
  print_camera(scene, info);
  std::printf("lights      %zu%s\n", scene.lights.size(),
              scene.lights.empty() ? " (the headlight)" : "");
  for (const auto& light : info["lights"]) {
    const bool point = light["kind"] == "point";
    const auto v = light[point ? "position" : "direction"], c = light["color"];
    std::printf("  %-11s %s (%g, %g, %g)  colour (%g, %g, %g)\n", point ? "point" : "directional",
                point ? "at" : "along", v[0].get<double>(), v[1].get<double>(), v[2].get<double>(),
                c[0].get<double>(), c[1].get<double>(), c[2].get<double>());
  }
  size_t listed = 0;
  for (const auto& object : info["object_list"]) {
    if (listed++ == kListedObjects) {
      std::printf("  ... and %zu more objects\n", scene.objects.size() - kListedObjects);
      break;
    }
    std::string visibility;
    if (object.contains("appear") || object.contains("disappear"))
      visibility =
          "  visible [" +
          (object.contains("appear") ? object["appear"].dump() : std::string("-inf")) + ", " +
          (object.contains("disappear") ? object["disappear"].dump() : std::string("inf")) + ")";
    std::printf("  object %-3zu %-20s %8zu triangles %3zu keys  %s%s\n", listed - 1,
                object["name"].get<std::string>().c_str(), object["triangles"].get<size_t>(),
                object["keys"].get<size_t>(), object["static"].get<bool>() ? "static" : "moving",
                visibility.c_str());
  }
}

}  // namespace

void register_info_command(CLI::App& app) {
  CLI::App* command = app.add_subcommand("info",
                                         "Print what a scene holds: triangles, vertices, objects, "
                                         "keyframes, duration, bounds, a model's animations, "
                                         "the camera and where it comes from");
  auto options = std::make_shared<InfoOptions>();
  command
      ->add_option("SCENE", options->scene,
                   "A built-in scene with parameters (wavy-sphere:triangles=40000), a .json scene "
                   "file or a model file")
      ->required();
  command->add_option("--animation", options->animation,
                      "Model files: the animation to play (name or index)");
  command->add_option("--keyrate", options->keyrate,
                      "Model files: resample at this many keys per second; mesh sequences: keys per second "
                      "(default 24)");
  add_camera_options(*command, options->camera);
  command->add_flag("--json", options->json, "Print JSON instead of text");
  command->footer(describe_scene_spec_syntax());
  command->callback([options] {
    if (!std::isfinite(options->keyrate) || options->keyrate < 0 || options->keyrate > kMaxKeyrate)
      throw InputError("--keyrate", "must be a number in [0, 1e6] (0: the model's own keys)");
    ModelOptions model;
    model.animation = options->animation;
    model.keyrate = options->keyrate;
    const CameraChoice camera = parse_camera_params(options->camera);
    model.camera = model_camera_choice(camera);
    ModelCatalog catalog;
    Scene scene = load_scene(options->scene, model, &catalog);
    apply_camera_choice(camera, scene);
    scene.validate(options->scene);
    nlohmann::json info = describe(options->scene, scene);
    if (is_mesh_sequence(options->scene))
      info["sequence"] = describe_sequence(options->scene, scene);
    if (!catalog.file.empty()) {
      info["animations"] = describe_animations(catalog);
      info["model_cameras"] = catalog.cameras;
    }
    if (options->json)
      std::printf("%s\n", info.dump(2).c_str());
    else
      print_text(scene, info);
  });
}

}  // namespace kinray
