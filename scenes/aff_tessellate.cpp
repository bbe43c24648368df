#include "scenes/aff_tessellate.h"

#include <cmath>

namespace kinray {

TriangleMesh tessellate_cone(const Vec3& base, double base_radius, const Vec3& apex,
                             double apex_radius) {
  const Vec3 axis = (apex - base).normalized();
  // Any unit vector perpendicular to the axis, then the third one of a right-handed frame.
  const Vec3 helper = std::abs(axis.x()) < 0.9 ? Vec3(1, 0, 0) : Vec3(0, 1, 0);
  const Vec3 u = axis.cross(helper).normalized(), v = axis.cross(u);
  TriangleMesh mesh;
  for (int s = 0; s < kConeSegments; ++s) {
    const double phi = 2 * M_PI * s / kConeSegments;
    const Vec3 radial = std::cos(phi) * u + std::sin(phi) * v;
    mesh.positions.push_back(base + base_radius * radial);
    mesh.positions.push_back(apex + apex_radius * radial);
  }
  for (uint32_t s = 0; s < uint32_t(kConeSegments); ++s) {
    const uint32_t next = (s + 1) % uint32_t(kConeSegments);
    const uint32_t b0 = 2 * s, a0 = 2 * s + 1, b1 = 2 * next, a1 = 2 * next + 1;
    // A zero radius collapses that ring to a point; skip the triangles that would be degenerate.
    if (base_radius > 0) mesh.triangles.push_back({b0, b1, a0});
    if (apex_radius > 0) mesh.triangles.push_back({a0, b1, a1});
  }
  return mesh;
}

TriangleMesh tessellate_sphere(const Vec3& center, double radius) {
  TriangleMesh mesh;
  mesh.positions.push_back(center + Vec3(0, radius, 0));  // north pole
  for (int r = 1; r < kSphereRings; ++r) {
    const double theta = M_PI * r / kSphereRings;
    for (int s = 0; s < kSphereSegments; ++s) {
      const double phi = 2 * M_PI * s / kSphereSegments;
      mesh.positions.push_back(center + radius * Vec3(std::sin(theta) * std::cos(phi),
                                                      std::cos(theta),
                                                      -std::sin(theta) * std::sin(phi)));
    }
  }
  const uint32_t south = uint32_t(mesh.positions.size());
  mesh.positions.push_back(center - Vec3(0, radius, 0));
  const uint32_t n = uint32_t(kSphereSegments);
  auto ring = [n](int r, uint32_t s) { return 1 + uint32_t(r - 1) * n + s % n; };
  for (uint32_t s = 0; s < n; ++s) {
    mesh.triangles.push_back({0, ring(1, s), ring(1, s + 1)});
    for (int r = 1; r + 1 < kSphereRings; ++r) {
      mesh.triangles.push_back({ring(r, s), ring(r + 1, s), ring(r + 1, s + 1)});
      mesh.triangles.push_back({ring(r, s), ring(r + 1, s + 1), ring(r, s + 1)});
    }
    mesh.triangles.push_back({ring(kSphereRings - 1, s), south, ring(kSphereRings - 1, s + 1)});
  }
  return mesh;
}

std::vector<Triangle> fan_triangles(size_t vertex_count) {
  std::vector<Triangle> triangles;
  for (size_t k = 1; k + 1 < vertex_count; ++k)
    triangles.push_back({0, uint32_t(k), uint32_t(k + 1)});
  return triangles;
}

}  // namespace kinray
