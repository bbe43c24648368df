#pragma once
// Small scenes whose pictures are known exactly, written directly in camera space: the camera
// stands at the origin with the identity orientation (looking down world -z) and a 90 degree fov,
// so the camera-space point (x, y, z) is the world point (x, y, -z) (fov scale 1 / tan 45 = 1 up
// to an ulp). With a square image, pixel (i, j) has the centre ray ((2i+1)/W - 1, 1 - (2j+1)/H, 1).
#include <string>
#include <vector>

#include "renderer/frame.h"
#include "scenes/camera_space.h"
#include "scenes/scene.h"

namespace kinray::test {

/// The camera-space point on the ray through image position (u, v) (in pixels, (0, 0) is the
/// top-left corner of a width x height image) at depth z.
inline Vec3 on_ray(double u, double v, double z, int width, int height) {
  const double x = (2.0 * u / width - 1.0) * (double(width) / double(height));
  const double y = 1.0 - 2.0 * v / height;
  return {x * z, y * z, z};
}

/// An object from camera-space key positions ([key][vertex]) at `times` (one key: static).
inline Object camera_space_object(const std::string& name, std::vector<Triangle> triangles,
                                  std::vector<std::vector<Vec3>> camera_positions,
                                  std::vector<double> times = {0.0}) {
  Object object;
  object.name = name;
  object.triangles = std::move(triangles);
  object.key_times = std::move(times);
  for (auto& key : camera_positions) {
    for (Vec3& p : key) p.z() = -p.z();
    object.key_positions.push_back(std::move(key));
  }
  return object;
}

/// A scene of `objects` seen by the 90 degree camera at the origin, shot [0, 1].
inline Scene analytic_scene(std::vector<Object> objects) {
  Scene scene;
  scene.name = "analytic";
  scene.objects = std::move(objects);
  scene.camera.keys = {CameraKey{}};
  scene.camera.keys[0].fov_y_degrees = 90;
  scene.validate("analytic scene");
  return scene;
}

/// Exact depth z = O / (E01 + E12 + E20) of the ray d on the plane of (p0, p1, p2)
/// (docs/design.md).
inline double plane_depth(const Vec3& p0, const Vec3& p1, const Vec3& p2, const Vec3& d) {
  const double o = p0.dot(p1.cross(p2));
  return o / (p0.cross(p1).dot(d) + p1.cross(p2).dot(d) + p2.cross(p0).dot(d));
}

/// The ID and depth buffers by brute force: every pixel's front-most triangle by the sign rule of
/// docs/design.md (the ray pierces a triangle iff its three edge functions have the sign of det(v0,
/// v1, v2)).
inline Frame exact_frame(const CameraSpaceScene& scene, int width, int height, double t) {
  Frame frame;
  frame.resize(width, height);
  frame.time = t;
  const PixelRays image{width, height};
  for (int j = 0; j < height; ++j)
    for (int i = 0; i < width; ++i) {
      const Vec3 d = image.direction(i, j);
      const size_t px = frame.index(i, j);
      double nearest = kInfinity;
      for (size_t o = 0; o < scene.objects.size(); ++o) {
        if (!scene.objects[o].visible(t)) continue;
        const std::vector<Triangle>& triangles = scene.triangles(o);
        for (size_t prim = 0; prim < triangles.size(); ++prim) {
          Vec3 v[3];
          for (int k = 0; k < 3; ++k)
            v[k] = scene.objects[o].position(triangles[prim][size_t(k)], t);
          const double det = v[0].dot(v[1].cross(v[2]));
          const double e01 = v[0].cross(v[1]).dot(d), e12 = v[1].cross(v[2]).dot(d),
                       e20 = v[2].cross(v[0]).dot(d);
          const bool pierced = det > 0 ? (e01 > 0 && e12 > 0 && e20 > 0)
                                       : det < 0 && (e01 < 0 && e12 < 0 && e20 < 0);
          if (!pierced) continue;
          const double z = det / (e01 + e12 + e20);
          if (z < nearest) {
            nearest = z;
            frame.object[px] = uint32_t(o);
            frame.prim[px] = uint32_t(prim);
            frame.depth[px] = float(z);
          }
        }
      }
    }
  return frame;
}

}  // namespace kinray::test
