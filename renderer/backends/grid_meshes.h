#pragma once
// The camera-space scene as the kinetic core's meshes (kinetic/motion/flightplan_mesh.h): what the
// kinetic grid and the kinetic trees consume.
#include <vector>

#include "kinetic/motion/flightplan_mesh.h"
#include "scenes/camera_space.h"

namespace kinray {

/// One FlightplanMesh per camera-space object, in order, pointing into `scene` (which must outlive
/// them).
[[nodiscard]] inline std::vector<FlightplanMesh> grid_meshes(const CameraSpaceScene& scene) {
  std::vector<FlightplanMesh> meshes;
  for (size_t o = 0; o < scene.objects.size(); ++o) {
    const CameraSpaceObject& cs = scene.objects[o];
    FlightplanMesh mesh;
    mesh.id = cs.object;
    mesh.key_times = cs.key_times;
    mesh.positions = cs.positions;
    mesh.vertex_count = cs.vertex_count;
    mesh.triangles = scene.triangles(o);
    mesh.appear = cs.appear;
    mesh.disappear = cs.disappear;
    mesh.is_static = cs.is_static;
    meshes.push_back(mesh);
  }
  return meshes;
}

}  // namespace kinray
