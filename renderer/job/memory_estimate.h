#pragma once
// What a render will need in memory, estimated before it starts, so that a request that cannot
// fit is refused in one line naming the flag at fault instead of ending in std::bad_alloc after
// minutes. The figures per vertex key, triangle and pixel are measured (memory_estimate.cpp).
#include <optional>
#include <string>

#include "renderer/job/render_job.h"
#include "scenes/camera_space.h"
#include "scenes/scene.h"

namespace kinray {

/// Bytes a render needs, by where they go.
struct MemoryEstimate {
  double scene = 0;           ///< key positions in world and camera space, normals, triangles
  double backend_scene = 0;   ///< the backend's per-triangle structures (grid records, BVH)
  double backend_pixels = 0;  ///< the backend's per-pixel structures (kinetic pixel entries)
  double frames = 0;          ///< frame buffers and the encoded images of one frame
  [[nodiscard]] double total() const { return scene + backend_scene + backend_pixels + frames; }
};

/// The sizes that drive the estimate: sums over objects of vertices x keys, as the world holds
/// them (a rigid object's vertices once) and as camera space does (the keys of the shot).
struct SceneSize {
  double triangles = 0, world_vertex_keys = 0, camera_vertex_keys = 0;
};

/// The sizes of a loaded scene whose camera space will hold the keys that `span` needs.
[[nodiscard]] SceneSize size_of(const Scene& scene,
                                std::optional<std::pair<double, double>> span = std::nullopt);
/// The sizes of a scene whose camera space is built.
[[nodiscard]] SceneSize size_of(const CameraSpaceScene& scene);

/// The estimate for a scene of `size` rendered at width x height by `backend`.
[[nodiscard]] MemoryEstimate estimate_render_memory(const SceneSize& size, int width, int height,
                                                    const std::string& backend);

/// Physical memory this process can still take, in bytes: MemAvailable of /proc/meminfo (else
/// sysconf's available pages), capped by a cgroup v2 memory.max; nullopt when unknown.
[[nodiscard]] std::optional<double> available_memory_bytes();

/// Throws InputError when the render `params` asks for cannot fit in available memory: before
/// loading (`scene` null) from a built-in scene's parameters, after loading from `scene` itself
/// (its camera space holding the keys `span` needs). The error names the scene spec or --size,
/// whichever needs more, and gives the estimate.
void check_render_memory(const RenderParams& params, const Scene* scene,
                         std::optional<std::pair<double, double>> span = std::nullopt);

}  // namespace kinray
