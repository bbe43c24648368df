#include "renderer/shading.h"

#include <algorithm>
#include <cmath>

#include "util/parallel.h"

namespace kinray {

ShadingInstant shading_instant(const CameraSpaceScene& scene, uint32_t object, double t) {
  return {locate(scene.objects[object].key_times, t), scene.tan_half_fov(t)};
}

SurfacePoint surface_point(const CameraSpaceScene& scene, const PixelRays& image, int i, int j,
                           uint32_t object, uint32_t prim, double t) {
  return surface_point(scene, image, i, j, object, prim, shading_instant(scene, object, t));
}

SurfacePoint surface_point(const CameraSpaceScene& scene, const PixelRays& image, int i, int j,
                           uint32_t object, uint32_t prim, const ShadingInstant& instant) {
  const KeySegment& at = instant.segment;
  const CameraSpaceObject& cs = scene.objects[object];
  const Object& source = scene.scene->objects[object];
  const Triangle& tri = source.triangles[prim];
  SurfacePoint surface;
  const Vec3 d = surface.ray = image.direction(i, j);
  const Vec3 p0 = surface.p0 = cs.position(tri[0], at);
  const Vec3 p1 = surface.p1 = cs.position(tri[1], at);
  const Vec3 p2 = surface.p2 = cs.position(tri[2], at);
  // Barycentrics of the ray's hit on the triangle's plane (Moller-Trumbore without the bounds
  // test: the backend has decided the hit; the fov folding is linear so they equal the true ones).
  const Vec3 e1 = p1 - p0, e2 = p2 - p0;
  const Vec3 pvec = d.cross(e2);
  const double det = e1.dot(pvec);
  double u = 1.0 / 3.0, v = 1.0 / 3.0;
  if (std::abs(det) > 0) {
    const Vec3 tvec = -p0;
    const Vec3 qvec = tvec.cross(e1);
    u = std::clamp(tvec.dot(pvec) / det, 0.0, 1.0);
    v = std::clamp(d.dot(qvec) / det, 0.0, 1.0 - u);
  }
  const float w0 = float(1.0 - u - v), w1 = float(u), w2 = float(v);
  Eigen::Vector3f n =
      w0 * cs.normal(tri[0], at) + w1 * cs.normal(tri[1], at) + w2 * cs.normal(tri[2], at);
  const float length = n.norm();
  surface.normal = length > 0 ? Eigen::Vector3f(n / length) : Eigen::Vector3f(0, 0, -1);
  surface.tan_half_fov = instant.tan_half_fov;
  surface.view = unfold(d, surface.tan_half_fov).normalized().cast<float>();

  const Material& material = scene.scene->materials[source.material];
  surface.base = material.base_color;
  if (material.texture >= 0 && !source.uvs.empty()) {
    const Vec2f uv = w0 * source.uvs[tri[0]] + w1 * source.uvs[tri[1]] + w2 * source.uvs[tri[2]];
    surface.base =
        surface.base.cwiseProduct(scene.scene->textures[size_t(material.texture)].sample(uv));
  }
  return surface;
}

Color shade_hit(const CameraSpaceScene& scene, const PixelRays& image, int i, int j,
                uint32_t object, uint32_t prim, double t) {
  return shade_hit(scene, image, i, j, object, prim, shading_instant(scene, object, t));
}

Color shade_hit(const CameraSpaceScene& scene, const PixelRays& image, int i, int j,
                uint32_t object, uint32_t prim, const ShadingInstant& instant) {
  const SurfacePoint surface = surface_point(scene, image, i, j, object, prim, instant);
  const float lambert = std::abs(surface.normal.dot(surface.view));
  return surface.base * (kAmbient + kDiffuse * lambert);
}

void shade_frame(const CameraSpaceScene& scene, Frame& frame, int threads) {
  const PixelRays image{frame.width, frame.height};
  parallel_for(size_t(frame.height), threads, [&](size_t row) {
    const int j = int(row);
    for (int i = 0; i < frame.width; ++i) {
      const size_t p = frame.index(i, j);
      frame.color[p] = frame.object[p] == kNoHit ? kBackgroundColor
                                                 : shade_hit(scene, image, i, j, frame.object[p],
                                                             frame.prim[p], frame.time);
    }
  });
}

}  // namespace kinray
