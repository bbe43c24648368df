#include "kinetic/motion/welded_triangles.h"

#include <algorithm>

namespace kinray {

std::vector<std::array<uint32_t, 3>> welded_triangles(const FlightplanMesh& mesh) {
  // -1, 0, 1: a's flightplan below, equal to, above b's (lexicographically over the keys)
  const auto compare = [&](uint32_t a, uint32_t b) {
    for (size_t key = 0; key < mesh.key_count(); ++key) {
      const Eigen::Vector3d &p = mesh.key_position(key, a), &q = mesh.key_position(key, b);
      for (int k = 0; k < 3; ++k)
        if (p[k] != q[k]) return p[k] < q[k] ? -1 : 1;
    }
    return 0;
  };
  // The vertices sorted by flightplan, equal ones by id: each run of equal flightplans starts at
  // its lowest id.
  std::vector<uint32_t> order(mesh.vertex_count);
  for (uint32_t v = 0; v < order.size(); ++v) order[v] = v;
  std::sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) {
    const int c = compare(a, b);
    return c != 0 ? c < 0 : a < b;
  });
  std::vector<uint32_t> same(mesh.vertex_count);
  uint32_t first = 0;
  for (size_t k = 0; k < order.size(); ++k) {
    if (k == 0 || compare(order[k - 1], order[k]) != 0) first = order[k];
    same[order[k]] = first;
  }
  std::vector<std::array<uint32_t, 3>> out(mesh.triangles.begin(), mesh.triangles.end());
  for (std::array<uint32_t, 3>& vs : out) {
    const std::array<uint32_t, 3> welded = {same[vs[0]], same[vs[1]], same[vs[2]]};
    if (welded[0] != welded[1] && welded[1] != welded[2] && welded[0] != welded[2]) vs = welded;
  }
  return out;
}

}  // namespace kinray
