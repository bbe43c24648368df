// The writer of JSON scene files: a scene as explicit vertex keys (docs/scene_format.md), which
// the reader loads back to the same scene (floats written as their shortest decimal).
#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <string>

#include "scenes/scene_file.h"
#include "util/input_error.h"

namespace kinray {
namespace {

using nlohmann::json;
namespace fs = std::filesystem;

json shortest(float x) {
  // The shortest decimal that reads back as the same float, not the 17 digits of its double.
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, x);
  return json(std::stod(std::string(buffer, result.ptr)));
}

json vec3_json(const Vec3& v) {
  return json::array({v.x(), v.y(), v.z()});
}

}  // namespace

void save_scene_file(const Scene& scene, const std::string& path) {
  json document;
  document["name"] = scene.name;
  document["shot"] = {{"begin", scene.time_begin}, {"end", scene.time_end}};
  json materials = json::array();
  for (const Material& material : scene.materials) {
    json m = {{"name", material.name},
              {"base_color",
               json::array({shortest(material.base_color.x()), shortest(material.base_color.y()),
                            shortest(material.base_color.z())})}};
    if (material.texture >= 0)
      m["texture"] = fs::absolute(scene.textures[size_t(material.texture)].path).string();
    materials.push_back(std::move(m));
  }
  // Material names must be unique in a file; fall back to indices when they are not.
  std::map<std::string, int> name_count;
  for (const Material& material : scene.materials) ++name_count[material.name];
  bool unique_names = true;
  for (const auto& [name, count] : name_count) unique_names &= count == 1;
  if (!unique_names)
    for (json& m : materials) m.erase("name");
  document["materials"] = std::move(materials);

  json camera_keys = json::array();
  for (const CameraKey& key : scene.camera.keys) {
    const Eigen::Quaterniond& q = key.orientation;
    camera_keys.push_back({{"time", key.time},
                           {"position", vec3_json(key.position)},
                           {"orientation", json::array({q.w(), q.x(), q.y(), q.z()})},
                           {"fov_y", key.fov_y_degrees}});
  }
  document["camera"] = {{"keys", std::move(camera_keys)}};
  if (!scene.lights.empty()) {
    json lights = json::array();
    for (const Light& light : scene.lights) {
      const json color = json::array(
          {shortest(light.color.x()), shortest(light.color.y()), shortest(light.color.z())});
      if (light.kind == Light::Kind::point)
        lights.push_back(
            {{"kind", "point"}, {"position", vec3_json(light.position)}, {"color", color}});
      else
        lights.push_back(
            {{"kind", "directional"}, {"direction", vec3_json(light.direction)}, {"color", color}});
    }
    document["lights"] = std::move(lights);
  }

  json objects = json::array();
  for (const Object& object : scene.objects) {
    json o = {{"kind", "mesh"}, {"name", object.name}, {"material", object.material}};
    if (std::isfinite(object.appear)) o["appear"] = object.appear;
    if (std::isfinite(object.disappear)) o["disappear"] = object.disappear;
    json triangles = json::array();
    for (const Triangle& t : object.triangles) triangles.push_back(json::array({t[0], t[1], t[2]}));
    o["triangles"] = std::move(triangles);
    if (!object.uvs.empty()) {
      json uvs = json::array();
      for (const Vec2f& uv : object.uvs)
        uvs.push_back(json::array({shortest(uv.x()), shortest(uv.y())}));
      o["uvs"] = std::move(uvs);
    }
    json keys = json::array();
    for (size_t k = 0; k < object.key_count(); ++k) {
      json vertices = json::array();
      for (uint32_t v = 0; v < object.vertex_count(); ++v)
        vertices.push_back(vec3_json(object.key_position(k, v)));
      keys.push_back({{"time", object.key_times[k]}, {"vertices", std::move(vertices)}});
    }
    o["keys"] = std::move(keys);
    objects.push_back(std::move(o));
  }
  document["objects"] = std::move(objects);

  std::ofstream out(path, std::ios::binary);
  if (!out) throw InputError(path, "cannot write the scene file");
  out << document.dump(1) << '\n';
  if (!out) throw InputError(path, "cannot write the scene file");
}

}  // namespace kinray
