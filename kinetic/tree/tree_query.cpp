#include "kinetic/tree/tree_query.h"

namespace kinray {

std::optional<TreeHit> brute_force_closest_hit(const TreeMeshes& meshes, const TreeRay& ray,
                                               const TreeFrame& frame) {
  std::optional<TreeHit> best;
  double s_max = ray.s_max;
  for (uint32_t m = 0; m < meshes.mesh_count(); ++m) {
    if (!meshes.mesh(m).present(frame.t)) continue;
    for (uint32_t tri = meshes.triangle_begin(m); tri < meshes.triangle_end(m); ++tri) {
      if (tri == ray.skip) continue;
      const auto& v = meshes.triangle(tri);
      const std::optional<double> s =
          ray_triangle(ray.origin, ray.direction, meshes.position(v[0], frame.blends),
                       meshes.position(v[1], frame.blends), meshes.position(v[2], frame.blends));
      if (s && *s > ray.s_min && *s < s_max) {
        best = TreeHit{tri, *s};
        s_max = *s;
      }
    }
  }
  return best;
}

}  // namespace kinray
