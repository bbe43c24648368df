#include "renderer/job/memory_estimate.h"

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "scenes/scene_loader.h"
#include "util/input_error.h"

namespace kinray {
namespace {

// Per vertex and key: a world position (Vec3, 24 bytes); in camera space a position (24) and a
// float normal (12). Per triangle: the scene's and camera space's index triples.
constexpr double kWorldBytesPerVertexKey = 24;
constexpr double kCameraBytesPerVertexKey = 36;
constexpr double kSceneBytesPerTriangle = 24;
// Measured with --stats (memory_bytes, pixel_memory_bytes) on wavy-sphere at 256x256: the kinetic
// grid takes 113 bytes per pixel and 530-680 bytes per triangle (records and certificates).
constexpr double kKineticBytesPerPixel = 120;
constexpr double kKineticBytesPerTriangle = 700;
// Embree: float vertices with padding and a BVH4 of LOW quality, about 150 bytes per triangle.
constexpr double kEmbreeBytesPerTriangle = 150;
// OSMesa: an RGBA colour and a float depth buffer per pixel, vertex arrays per triangle.
constexpr double kOsmesaBytesPerPixel = 16;
constexpr double kOsmesaBytesPerTriangle = 64;
// A Frame (object, prim, depth, linear colour: 24 bytes) and the encoded colour, id and depth
// images of one frame (3 + 6 + 4 bytes), with room for the encoder's buffers.
constexpr double kFrameBytesPerPixel = 40;

std::string gigabytes(double bytes) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1f GB", bytes / 1e9);
  return text;
}

/// A built-in's size from its parameters: its meshes have about one vertex per two triangles.
std::optional<SceneSize> size_of_builtin(const std::string& spec) {
  const std::optional<ProceduralParams> params = builtin_scene_params(spec);
  if (!params) return std::nullopt;
  const double keys = std::ceil(params->duration * params->keyrate - 1e-9) + 1;
  const double vertex_keys = params->triangles / 2 * keys;
  return SceneSize{params->triangles, vertex_keys, vertex_keys};
}

/// Adds `object`'s triangles and world-space vertex keys (a rigid object's vertices once).
void add_world_size(const Object& object, SceneSize& size) {
  const double vertices = double(object.vertex_count());
  size.triangles += double(object.triangles.size());
  size.world_vertex_keys += object.rigid ? vertices : double(object.key_position_sets()) * vertices;
}

}  // namespace

SceneSize size_of(const Scene& scene, std::optional<std::pair<double, double>> span) {
  SceneSize size;
  for (size_t o = 0; o < scene.objects.size(); ++o) {
    add_world_size(scene.objects[o], size);
    size.camera_vertex_keys += double(camera_space_key_times(scene, o, span).size()) *
                               double(scene.objects[o].vertex_count());
  }
  return size;
}

SceneSize size_of(const CameraSpaceScene& scene) {
  SceneSize size;
  for (const Object& object : scene.scene->objects) add_world_size(object, size);
  for (const CameraSpaceObject& object : scene.objects)
    size.camera_vertex_keys += double(object.key_times.size()) * double(object.vertex_count);
  return size;
}

MemoryEstimate estimate_render_memory(const SceneSize& size, int width, int height,
                                      const std::string& backend) {
  const double pixels = double(width) * double(height);
  MemoryEstimate estimate;
  estimate.scene = size.world_vertex_keys * kWorldBytesPerVertexKey +
                   size.camera_vertex_keys * kCameraBytesPerVertexKey +
                   size.triangles * kSceneBytesPerTriangle;
  estimate.frames = pixels * kFrameBytesPerPixel;
  // auto tries the kinetic grid only when it fits (renderer/auto_backend.h)
  if (backend == "kinetic") {
    estimate.backend_scene = size.triangles * kKineticBytesPerTriangle;
    estimate.backend_pixels = pixels * kKineticBytesPerPixel;
  } else if (backend == "embree" || backend == "auto") {
    estimate.backend_scene = size.triangles * kEmbreeBytesPerTriangle;
  } else {
    estimate.backend_scene = size.triangles * kOsmesaBytesPerTriangle;
    estimate.backend_pixels = pixels * kOsmesaBytesPerPixel;
  }
  return estimate;
}

std::optional<double> available_memory_bytes() {
  std::optional<double> available;
  std::ifstream meminfo("/proc/meminfo");
  for (std::string line; std::getline(meminfo, line);) {
    std::istringstream fields(line);
    std::string key;
    double kilobytes = 0;
    if (fields >> key >> kilobytes && key == "MemAvailable:") available = kilobytes * 1024;
  }
  if (!available) {
    const long pages = ::sysconf(_SC_AVPHYS_PAGES), page = ::sysconf(_SC_PAGESIZE);
    if (pages > 0 && page > 0) available = double(pages) * double(page);
  }
  double limit = 0, used = 0;
  if ((std::ifstream("/sys/fs/cgroup/memory.max") >> limit) &&
      (std::ifstream("/sys/fs/cgroup/memory.current") >> used) && limit > used)
    available = available ? std::min(*available, limit - used) : limit - used;
  return available;
}

void check_render_memory(const RenderParams& params, const Scene* scene,
                         std::optional<std::pair<double, double>> span) {
  const std::optional<SceneSize> size =
      scene ? std::optional<SceneSize>(size_of(*scene, span)) : size_of_builtin(params.scene);
  const std::optional<double> available = available_memory_bytes();
  if (!size || !available) return;
  const MemoryEstimate estimate =
      estimate_render_memory(*size, params.width, params.height, params.backend);
  if (estimate.total() <= *available) return;
  const bool pixels_dominate =
      estimate.frames + estimate.backend_pixels > estimate.scene + estimate.backend_scene;
  throw InputError(
      pixels_dominate ? "--size" : params.scene,
      "this render needs about " + gigabytes(estimate.total()) + " of memory (scene " +
          gigabytes(estimate.scene) + ", " + params.backend + " backend " +
          gigabytes(estimate.backend_scene + estimate.backend_pixels) + ", frames " +
          gigabytes(estimate.frames) + ") and the machine has " + gigabytes(*available) +
          " available; " +
          (pixels_dominate ? "give a smaller --size" : "give fewer triangles or keys") +
          (params.backend == "kinetic" ? " or --backend embree" : ""));
}

}  // namespace kinray
