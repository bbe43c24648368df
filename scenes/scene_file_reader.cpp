// The reader of JSON scene files (docs/scene_format.md): materials, objects (meshes, built-ins,
// models, primitives) with their keys, the camera, lights and the shot. Every malformed value is
// an InputError naming the file and the JSON pointer (json_node.h).
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <optional>
#include <sstream>

#include "scenes/camera_space.h"
#include "scenes/json_node.h"
#include "scenes/json_unique_keys.h"
#include "scenes/mesh_builders.h"
#include "scenes/model_import.h"
#include "scenes/procedural.h"
#include "scenes/scene_file.h"
#include "scenes/scene_file_keys.h"
#include "scenes/texture_image.h"
#include "util/image_signature.h"
#include "util/png_chunks.h"
#include "util/input_error.h"

namespace kinray {
namespace {

using nlohmann::json;
namespace fs = std::filesystem;

// Guards against files that would exhaust memory rather than describe a scene.
constexpr double kMaxPrimitiveTriangles = 5e7;

/// The fast path of the large arrays (vertices, triangles, uvs): reads `n` finite numbers of a
/// JSON array straight away; on anything else returns false, and the caller goes through JsonNode
/// for the precise error.
bool read_numbers(const json& value, size_t n, double* out) {
  if (!value.is_array() || value.size() != n) return false;
  for (size_t i = 0; i < n; ++i) {
    const json& x = value[i];
    if (!x.is_number()) return false;
    out[i] = x.get<double>();
    if (!std::isfinite(out[i])) return false;
  }
  return true;
}

std::vector<Vec3> parse_vertices(const JsonNode& node) {
  std::vector<Vec3> vertices(node.size());
  for (size_t v = 0; v < vertices.size(); ++v)
    if (!read_numbers(node.value()[v], 3, vertices[v].data())) vertices[v] = node[v].vec3();
  return vertices;
}

float to_float_channel(const JsonNode& node) {
  const double x = node.number();
  if (x < 0) node.fail("colour channels must be >= 0");
  return float(x);
}

Texture read_texture_file(const JsonNode& where, const fs::path& path) {
  std::error_code error;
  if (!fs::is_regular_file(path, error))
    where.fail("cannot read texture " + path.string() +
               (fs::exists(path, error) ? " (not a regular file)" : " (no such file)"));
  const ImageSignature format = image_signature_of_file(path);
  if (!opencv_may_decode(format))
    where.fail("cannot read texture " + path.string() + " (not a " +
               std::string(kDecodableImageFormats) + " file)");
  if (format == ImageSignature::png)
    if (const std::optional<std::string> problem = png_file_chunk_problem(path))
      where.fail("cannot read texture " + path.string() + ": " + *problem);
  cv::Mat image;
  try {
    image = cv::imread(path.string(), cv::IMREAD_COLOR);
  } catch (const cv::Exception& decode_error) {
    where.fail("cannot decode texture " + path.string() + ": " + decode_error.what());
  }
  if (image.empty())
    where.fail("cannot read texture " + path.string() + " (not an image OpenCV can decode)");
  if (size_t(image.cols) * size_t(image.rows) > kMaxTexels)
    where.fail("texture " + path.string() + " has more than 8192 x 8192 texels");
  if (image.depth() != CV_8U) image.convertTo(image, CV_8U, 1.0 / 256);
  return texture_from_bgr(image, path.string());
}

/// Everything being assembled while a file is read.
struct Reader {
  std::string file;
  fs::path directory;
  Scene scene;
  std::map<std::string, uint32_t> material_by_name;
  bool has_materials = false;                ///< the file lists materials: the first is the default
  std::optional<uint32_t> default_material;  ///< else one is made when an object needs it
  std::optional<Scene> first_provided;  ///< camera and shot of the first builtin or model object
  std::vector<Light> model_lights;      ///< lights brought by builtin and model objects

  [[nodiscard]] fs::path resolve(const std::string& relative) const {
    const fs::path p(relative);
    return p.is_absolute() ? p : directory / p;
  }

  void read_materials(const JsonNode& root) {
    const auto materials = root.find("materials");
    scene.materials.clear();
    if (!materials) return;
    has_materials = true;
    std::map<std::string, int> texture_by_path;
    for (size_t m = 0; m < materials->size(); ++m) {
      const JsonNode node = (*materials)[m];
      node.expect_object({"name", "base_color", "texture"});
      Material material;
      if (auto name = node.find("name")) {
        material.name = name->string();
        if (!material_by_name.emplace(material.name, uint32_t(m)).second)
          name->fail("material name '" + material.name + "' is used twice");
      }
      if (auto color = node.find("base_color")) {
        color->expect_size(3);
        material.base_color = Color(to_float_channel((*color)[0]), to_float_channel((*color)[1]),
                                    to_float_channel((*color)[2]));
      }
      if (auto texture = node.find("texture")) {
        const fs::path path = resolve(texture->string());
        const auto [it, inserted] =
            texture_by_path.emplace(path.string(), int(scene.textures.size()));
        if (inserted) scene.textures.push_back(read_texture_file(*texture, path));
        material.texture = it->second;
      }
      scene.materials.push_back(material);
    }
    if (scene.materials.empty()) materials->fail("expected at least one material");
  }

  [[nodiscard]] uint32_t material_of(const JsonNode& object) {
    const auto material = object.find("material");
    if (!material) {
      if (has_materials) return 0;
      // Made on demand, so that a file of builtin objects reproduces the built-in's materials
      // exactly.
      if (!default_material) {
        default_material = uint32_t(scene.materials.size());
        scene.materials.push_back(Material{"default"});
      }
      return *default_material;
    }
    if (material->value().is_string()) {
      const std::string name = material->string();
      const auto it = material_by_name.find(name);
      if (it != material_by_name.end()) return it->second;
      std::string valid;
      for (const auto& [n, index] : material_by_name) valid += (valid.empty() ? "" : ", ") + n;
      material->fail("no material called '" + name + "'" +
                     (valid.empty() ? "" : "; the materials are " + valid));
    }
    return uint32_t(material->integer(0, int(scene.materials.size()) - 1));
  }

  /// Appends a whole scene brought in by a builtin or model object, remapping its materials.
  void merge(Scene&& other, const JsonNode& object, const std::string& prefix) {
    const std::optional<uint32_t> material =
        object.has("material") ? std::optional(material_of(object)) : std::nullopt;
    const uint32_t material_offset = uint32_t(scene.materials.size());
    const int texture_offset = int(scene.textures.size());
    for (Material m : other.materials) {
      if (m.texture >= 0) m.texture += texture_offset;
      scene.materials.push_back(std::move(m));
    }
    for (Texture& t : other.textures) scene.textures.push_back(std::move(t));
    const Placement placement = parse_placement(object, true);
    merge_lights(other.lights, placement);
    for (Object& o : other.objects) {
      o.material = material ? *material : o.material + material_offset;
      if (!prefix.empty()) o.name = prefix + "/" + o.name;
      read_visibility(object, o);
      apply_placement(o, placement);
      scene.objects.push_back(std::move(o));
    }
    other.objects.clear();
    if (!first_provided) first_provided = std::move(other);
  }

  /// Lights a builtin or model object brings, moved as its meshes are: lights do not move in
  /// kinray, so TRS keys apply as they stand at the first key.
  void merge_lights(const std::vector<Light>& lights, const Placement& placement) {
    Eigen::Affine3d matrix = Eigen::Affine3d::Identity();
    if (!placement.keys.empty()) matrix = placement.at(placement.times.front()).matrix();
    if (placement.rest) matrix = matrix * *placement.rest;
    for (Light light : lights) {
      light.position = matrix * light.position;
      const Vec3 direction = matrix.linear() * light.direction;
      if (direction.norm() > 0) light.direction = direction.normalized();
      model_lights.push_back(light);
    }
  }

  /// "lights": point and directional lights in world space; when the key is absent the lights of
  /// the file's builtin and model objects are used.
  void read_lights(const JsonNode& root) {
    const auto lights = root.find("lights");
    if (!lights) {
      scene.lights = model_lights;
      return;
    }
    for (size_t l = 0; l < lights->size(); ++l) {
      const JsonNode node = (*lights)[l];
      Light light;
      const std::string kind = node.at("kind").string();
      if (kind == "point") {
        node.expect_object({"kind", "position", "color"});
        light.kind = Light::Kind::point;
        light.position = node.at("position").vec3();
      } else if (kind == "directional") {
        node.expect_object({"kind", "direction", "color"});
        light.kind = Light::Kind::directional;
        const Vec3 direction = node.at("direction").vec3();
        if (!(direction.norm() > 0)) node.at("direction").fail("the direction must not be zero");
        // A unit vector (as save_scene_file writes) is kept bit for bit.
        light.direction =
            std::abs(direction.norm() - 1) > 1e-12 ? Vec3(direction.normalized()) : direction;
      } else {
        node.at("kind").fail("unknown light kind '" + kind + "'; the kinds are point, directional");
      }
      if (auto color = node.find("color")) {
        const Vec3 rgb = color->vec3();
        if ((rgb.array() < 0).any()) color->fail("light colours must be >= 0");
        light.color = rgb.cast<float>();
      }
      scene.lights.push_back(light);
    }
  }

  static void read_visibility(const JsonNode& node, Object& object) {
    if (auto appear = node.find("appear")) object.appear = appear->number();
    if (auto disappear = node.find("disappear")) {
      object.disappear = disappear->number();
      if (!(object.disappear > object.appear))
        disappear->fail("an object must disappear after it appears (appear = " +
                        std::to_string(object.appear) + ")");
    }
  }

  void read_mesh(const JsonNode& node, Object& object) {
    const JsonNode triangles = node.at("triangles");
    object.triangles.resize(triangles.size());
    for (size_t f = 0; f < object.triangles.size(); ++f) {
      const json& raw = triangles.value()[f];
      if (raw.is_array() && raw.size() == 3 && raw[0].is_number_unsigned() &&
          raw[1].is_number_unsigned() && raw[2].is_number_unsigned() &&
          raw[0].get<uint64_t>() <= UINT32_MAX && raw[1].get<uint64_t>() <= UINT32_MAX &&
          raw[2].get<uint64_t>() <= UINT32_MAX) {
        object.triangles[f] = {raw[0].get<uint32_t>(), raw[1].get<uint32_t>(),
                               raw[2].get<uint32_t>()};
        continue;
      }
      const JsonNode tri = triangles[f];
      tri.expect_size(3);
      for (int c = 0; c < 3; ++c) {
        const uint64_t index = tri[c].unsigned_integer();
        if (index > UINT32_MAX) tri[c].fail("vertex index too large");
        object.triangles[f][size_t(c)] = uint32_t(index);
      }
    }
    const auto keys = node.find("keys");
    const bool vertex_keys = keys && keys->size() > 0 && (*keys)[0].has("vertices");
    if (vertex_keys) {
      if (auto rest = node.find("vertices"))
        rest->fail(
            "give either 'vertices' (moved by transform keys) or a 'vertices' array in every key, "
            "not both");
      if (auto keyrate = node.find("keyrate"))
        keyrate->fail("'keyrate' resamples transform keys; these keys are vertex arrays");
      std::optional<double> previous;
      for (size_t k = 0; k < keys->size(); ++k) {
        const JsonNode key = (*keys)[k];
        if (!key.has("vertices"))
          key.fail(
              "missing key 'vertices': every key of this mesh is a vertex array, since key 0 is");
        key.expect_object({"time", "vertices"});
        previous = parse_key_time(key, previous);
        object.key_times.push_back(*previous);
        object.key_positions.push_back(parse_vertices(key.at("vertices")));
        if (object.key_positions.back().size() != object.key_positions[0].size())
          key.at("vertices")
              .fail("has " + std::to_string(object.key_positions.back().size()) +
                    " vertices, key 0 has " + std::to_string(object.key_positions[0].size()));
      }
      apply_placement(object, parse_placement(node, false));
    } else {
      if (keys)
        for (size_t k = 0; k < keys->size(); ++k)
          if ((*keys)[k].has("vertices"))
            (*keys)[k].at("vertices").fail("key 0 is a transform key, so every key must be one");
      object.key_times = {0.0};
      object.key_positions = {parse_vertices(node.at("vertices"))};
      apply_placement(object, parse_placement(node, true));
    }
    const size_t nv = object.vertex_count();
    for (size_t f = 0; f < object.triangles.size(); ++f)
      for (int c = 0; c < 3; ++c)
        if (object.triangles[f][size_t(c)] >= nv)
          triangles[f][size_t(c)].fail("vertex index " +
                                       std::to_string(object.triangles[f][size_t(c)]) +
                                       " out of range (" + std::to_string(nv) + " vertices)");
    if (auto uvs = node.find("uvs")) {
      if (uvs->size() != nv)
        uvs->fail("has " + std::to_string(uvs->size()) + " uvs for " + std::to_string(nv) +
                  " vertices");
      for (size_t v = 0; v < nv; ++v) {
        double uv[2];
        if (!read_numbers(uvs->value()[v], 2, uv)) {
          const JsonNode node_uv = (*uvs)[v];
          node_uv.expect_size(2);
          uv[0] = node_uv[0].number();
          uv[1] = node_uv[1].number();
        }
        object.uvs.emplace_back(float(uv[0]), float(uv[1]));
      }
    }
  }

  Mesh read_primitive(const JsonNode& node, const std::string& kind) {
    if (kind == "sphere") {
      const double radius = node.has("radius") ? node.at("radius").positive() : 1.0;
      if (node.has("triangles") && node.has("subdivisions"))
        node.at("subdivisions").fail("give either 'triangles' or 'subdivisions', not both");
      int n = 9;  // 972 triangles
      if (auto triangles = node.find("triangles")) {
        const double count = triangles->positive();
        if (count > kMaxPrimitiveTriangles) triangles->fail("at most 5e7 triangles");
        n = cube_subdivisions_for(count);
      }
      if (auto subdivisions = node.find("subdivisions")) n = subdivisions->integer(1, 2000);
      return make_sphere(radius, n);
    }
    if (kind == "box") {
      Vec3 size = Vec3::Ones();
      if (auto s = node.find("size")) {
        size = s->value().is_array() ? s->vec3() : Vec3::Constant(s->number());
        if (!(size.array() > 0).all()) s->fail("box edge lengths must be > 0");
      }
      const int n = node.has("subdivisions") ? node.at("subdivisions").integer(1, 2000) : 1;
      return make_box(size, n);
    }
    // grid
    double sx = 1, sz = 1;
    if (auto s = node.find("size")) {
      if (s->value().is_array()) {
        s->expect_size(2);
        sx = (*s)[0].positive();
        sz = (*s)[1].positive();
      } else {
        sx = sz = s->positive();
      }
    }
    int nx = 1, nz = 1;
    if (auto s = node.find("subdivisions")) {
      if (s->value().is_array()) {
        s->expect_size(2);
        nx = (*s)[0].integer(1, 100000);
        nz = (*s)[1].integer(1, 100000);
      } else {
        nx = nz = s->integer(1, 100000);
      }
      if (2.0 * nx * nz > kMaxPrimitiveTriangles) s->fail("at most 5e7 triangles");
    }
    return make_grid(sx, sz, nx, nz);
  }

  void read_object(const JsonNode& node, size_t index) {
    const std::string kind = node.at("kind").string();
    const std::string name =
        node.has("name") ? node.at("name").string() : kind + " " + std::to_string(index);
    if (kind == "mesh") {
      node.expect_object({"kind", "name", "material", "appear", "disappear", "vertices",
                          "triangles", "uvs", "keys", "transform", "keyrate"});
      Object object;
      object.name = name;
      object.material = material_of(node);
      read_visibility(node, object);
      read_mesh(node, object);
      scene.objects.push_back(std::move(object));
    } else if (kind == "sphere" || kind == "box" || kind == "grid") {
      if (kind == "sphere")
        node.expect_object({"kind", "name", "material", "appear", "disappear", "radius",
                            "triangles", "subdivisions", "keys", "transform", "keyrate"});
      else
        node.expect_object({"kind", "name", "material", "appear", "disappear", "size",
                            "subdivisions", "keys", "transform", "keyrate"});
      Object object = make_static_object(name, read_primitive(node, kind), material_of(node));
      read_visibility(node, object);
      apply_placement(object, parse_placement(node, true));
      scene.objects.push_back(std::move(object));
    } else if (kind == "model") {
      node.expect_object({"kind", "name", "material", "appear", "disappear", "path", "animation",
                          "keyrate", "keys", "transform"});
      const JsonNode path_node = node.at("path");
      const fs::path path = resolve(path_node.string());
      if (!fs::exists(path)) path_node.fail("no such file: " + path.string());
      ModelOptions options;
      if (auto animation = node.find("animation"))
        options.animation = animation->value().is_number_integer()
                                ? std::to_string(animation->integer(0, 1 << 30))
                                : animation->string();
      // The keyrate resamples the model's own animation; transform keys are resampled too.
      if (auto keyrate = node.find("keyrate")) options.keyrate = keyrate->positive();
      Scene model;
      try {
        model = load_model(path.string(), options);
      } catch (const InputError& error) {
        path_node.fail(error.what());
      }
      merge(std::move(model), node, node.has("name") ? name : "");
    } else if (kind == "builtin") {
      node.expect_object({"kind", "name", "material", "appear", "disappear", "scene", "params"});
      const JsonNode scene_node = node.at("scene");
      std::map<std::string, double> params;
      if (auto p = node.find("params")) {
        if (!p->value().is_object())
          p->fail("expected an object of numbers, like {\"triangles\": 2000}");
        for (const auto& item : p->value().items())
          params[item.key()] =
              JsonNode(item.value(), file, p->pointer() + "/" + escape_pointer_token(item.key()))
                  .number();
      }
      Scene builtin;
      try {
        builtin = make_builtin_scene(scene_node.string(), params);
      } catch (const InputError& error) {
        (node.has("params") && is_builtin_scene(scene_node.string()) ? node.at("params")
                                                                     : scene_node)
            .fail(error.what());
      }
      merge(std::move(builtin), node, node.has("name") ? name : "");
    } else {
      node.at("kind").fail("unknown object kind '" + kind +
                           "'; the kinds are mesh, sphere, box, grid, model, builtin");
    }
  }

  void read_camera(const JsonNode& root) {
    const auto camera = root.find("camera");
    if (!camera) {
      if (!first_provided)
        root.fail(
            "missing key 'camera' (only a file with a builtin or model object may leave it out, "
            "and take theirs)");
      scene.camera = first_provided->camera;
      scene.camera_source = first_provided->camera_source;
      return;
    }
    camera->expect_object({"keys", "keyrate"});
    const JsonNode keys = camera->at("keys");
    if (keys.size() == 0) keys.fail("expected at least one camera key");
    Camera result;
    result.keys.clear();
    std::optional<double> previous;
    for (size_t k = 0; k < keys.size(); ++k) {
      const JsonNode key = keys[k];
      key.expect_object({"time", "position", "look_at", "up", "orientation", "fov_y"});
      double time = 0;
      if (keys.size() > 1 || key.has("time")) time = *(previous = parse_key_time(key, previous));
      const Vec3 position = key.at("position").vec3();
      double fov = 45;
      if (auto fov_node = key.find("fov_y")) {
        fov = fov_node->number();
        if (!(fov > 0.5 && fov < 179.5)) fov_node->fail("fov_y must lie in (0.5, 179.5) degrees");
      }
      if (key.has("look_at") == key.has("orientation"))
        key.fail(
            "give either 'look_at' (with an optional 'up') or 'orientation' (a quaternion [w, x, "
            "y, z])");
      if (auto target_node = key.find("look_at")) {
        const Vec3 target = target_node->vec3();
        if (!((target - position).norm() > 1e-12))
          target_node->fail("the camera looks at its own position");
        const Vec3 up = key.has("up") ? key.at("up").vec3() : Vec3::UnitY();
        if (!(up.norm() > 1e-12)) key.at("up").fail("the up vector must not be zero");
        if (key.has("up") &&
            !(up.normalized().cross((target - position).normalized()).norm() > 1e-9))
          key.at("up").fail("the up vector is parallel to the viewing direction");
        result.keys.push_back(Camera::look_at(time, position, target, up, fov));
      } else {
        if (auto up = key.find("up"))
          up->fail("'up' goes with 'look_at'; an orientation says where up is");
        result.keys.push_back(
            CameraKey{time, position, parse_quaternion(key.at("orientation")), fov});
      }
    }
    if (auto keyrate = camera->find("keyrate")) {
      const double rate = keyrate->positive();
      std::vector<double> times;
      for (const CameraKey& key : result.keys) times.push_back(key.time);
      Camera fine;
      fine.keys.clear();
      for (double t : resample(times, rate, *keyrate)) fine.keys.push_back(result.at(t));
      // Camera::at returns the original keys exactly at their times; keep their own time stamps.
      result = std::move(fine);
    }
    scene.camera = std::move(result);
  }

  void read_shot(const JsonNode& root) {
    const auto shot = root.find("shot");
    if (!shot) {
      if (!first_provided)
        root.fail(
            "missing key 'shot' (only a file with a builtin or model object may leave it out, and "
            "take theirs)");
      scene.time_begin = first_provided->time_begin;
      scene.time_end = first_provided->time_end;
      return;
    }
    shot->expect_object({"begin", "end"});
    scene.time_begin = shot->at("begin").number();
    scene.time_end = shot->at("end").number();
    if (!(scene.time_end > scene.time_begin))
      shot->at("end").fail(
          "the shot must end after it begins (begin = " + std::to_string(scene.time_begin) +
          ", end = " + std::to_string(scene.time_end) + ")");
  }

  void read(const json& document) {
    const JsonNode root(document, file, "");
    root.expect_object({"name", "description", "shot", "materials", "camera", "lights", "objects"});
    scene.name = root.has("name") ? root.at("name").string() : fs::path(file).stem().string();
    if (auto description = root.find("description")) (void)description->string();
    read_materials(root);
    const JsonNode objects = root.at("objects");
    for (size_t o = 0; o < objects.size(); ++o) read_object(objects[o], o);
    read_camera(root);
    read_lights(root);
    read_shot(root);
    if (scene.materials.empty()) scene.materials.push_back(Material{"default"});
  }
};

/// Line and column (both from 1) of byte `offset` in `text`.
std::pair<size_t, size_t> line_and_column(const std::string& text, size_t offset) {
  offset = std::min(offset, text.size());
  size_t line = 1, column = 1;
  for (size_t i = 0; i < offset; ++i) {
    if (text[i] == '\n') {
      ++line;
      column = 1;
    } else {
      ++column;
    }
  }
  return {line, column};
}

}  // namespace

Scene parse_scene_file(const std::string& text, const std::string& path) {
  json document;
  try {
    document = parse_json_with_unique_keys(text);
  } catch (const DuplicateJsonKey& error) {
    throw InputError(path + ": " + error.pointer + "/" + error.key,
                     "is given twice in one object (JSON would keep only the last)");
  } catch (const json::parse_error& error) {
    // nlohmann's byte is one past the character it stopped at.
    const auto [line, column] = line_and_column(text, error.byte > 0 ? error.byte - 1 : 0);
    std::string message = error.what();
    const size_t colon = message.find(": ");
    if (message.find("parse error") != std::string::npos && colon != std::string::npos)
      message = message.substr(colon + 2);
    throw InputError(path + ":" + std::to_string(line) + ":" + std::to_string(column),
                     "JSON syntax error: " + message);
  } catch (const json::exception& error) {
    // A number too large for a double ("number overflow parsing '1e999'") carries no position:
    // find the token in the text.
    std::string where = path;
    const std::string message = error.what();
    const size_t open = message.find('\''), close = message.rfind('\'');
    if (open != std::string::npos && close > open + 1) {
      const size_t at = text.find(message.substr(open + 1, close - open - 1));
      if (at != std::string::npos) {
        const auto [line, column] = line_and_column(text, at);
        where += ":" + std::to_string(line) + ":" + std::to_string(column);
      }
    }
    throw InputError(where, std::string("JSON error: ") + message.substr(message.find(']') + 2));
  }
  Reader reader;
  reader.file = path;
  reader.directory = fs::path(path).parent_path();
  reader.read(document);
  reader.scene.validate(path);
  return std::move(reader.scene);
}

Scene load_scene_file(const std::string& path) {
  std::error_code error;
  if (!fs::is_regular_file(path, error))
    throw InputError(path, fs::exists(path, error) ? "not a regular file" : "no such scene file");
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  if (!in && !in.eof()) throw InputError(path, "cannot read the file");
  return parse_scene_file(text.str(), path);
}

}  // namespace kinray
