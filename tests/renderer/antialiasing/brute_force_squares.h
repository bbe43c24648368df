#pragma once
// Brute-force companions of the exact antialiasing tests: a conservative overlapping set per
// pixel square (every triangle whose projected box meets the square, and every triangle with a
// vertex at or behind the eye plane), and a stratified box-filter reference of the same shading,
// with its nearest hits by Moller-Trumbore in 3D rather than by the half-planes under test.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "renderer/antialiasing/exact_pixel.h"
#include "renderer/antialiasing/square_visibility.h"
#include "renderer/frame.h"
#include "renderer/shading.h"
#include "scenes/camera_space.h"

namespace kinray::test {

/// Every visible triangle of `scene` at t, with its camera-space vertices.
struct SceneTriangles {
  std::vector<TriangleRef> refs;
  std::vector<TriangleAtInstant> at;
  std::vector<Eigen::Vector4d> boxes;  ///< projected (x0, y0, x1, y1) of the part in front
};

inline SceneTriangles scene_triangles(const CameraSpaceScene& scene, double t) {
  SceneTriangles out;
  for (uint32_t o = 0; o < scene.objects.size(); ++o) {
    if (!scene.objects[o].visible(t)) continue;
    const ShadingInstant instant = shading_instant(scene, o, t);
    for (uint32_t prim = 0; prim < scene.triangles(o).size(); ++prim) {
      const TriangleAtInstant& tri =
          out.at.emplace_back(triangle_at_instant(scene, o, prim, instant));
      out.refs.push_back({o, prim});
      // The projected box of the part in front of the plane z = 1e-9 (clipped in 3D, the
      // textbook way, not by the image-plane half-planes under test).
      constexpr double kNear = 1e-9;
      const std::array<Vec3, 3> p = {tri.p0, tri.p1, tri.p2};
      Eigen::Vector4d box(kInfinity, kInfinity, -kInfinity, -kInfinity);
      auto add = [&](const Vec3& q) {
        box = Eigen::Vector4d(std::min(box[0], q.x() / q.z()), std::min(box[1], q.y() / q.z()),
                              std::max(box[2], q.x() / q.z()), std::max(box[3], q.y() / q.z()));
      };
      for (size_t k = 0; k < 3; ++k) {
        const Vec3 &a = p[k], &b = p[(k + 1) % 3];
        if (a.z() >= kNear) add(a);
        if ((a.z() < kNear) != (b.z() < kNear))
          add(a + (b - a) * ((kNear - a.z()) / (b.z() - a.z())));
      }
      out.boxes.push_back(box);
    }
  }
  return out;
}

/// Indices into `triangles` of those whose box meets `square` (a superset of the overlapping).
inline std::vector<size_t> overlapping(const SceneTriangles& triangles, const PixelSquare& s) {
  std::vector<size_t> out;
  for (size_t k = 0; k < triangles.boxes.size(); ++k) {
    const Eigen::Vector4d& b = triangles.boxes[k];
    if (b[0] <= s.x1 && b[2] >= s.x0 && b[1] <= s.y1 && b[3] >= s.y0) out.push_back(k);
  }
  return out;
}

/// The exact read-out of a frame at t with each pixel's set found by brute force (the boxes'
/// superset, which the read-out must reduce to what is seen); its counters added to `stats`.
inline std::vector<Color> brute_force_exact_colours(const CameraSpaceScene& scene, int width,
                                                    int height, double t,
                                                    const SceneTriangles& triangles,
                                                    ExactPixels::Stats* stats = nullptr) {
  Frame frame;
  frame.resize(width, height);
  frame.time = t;
  const PixelRays image{width, height};
  std::vector<std::vector<TriangleRef>> sets(frame.pixel_count());
  for (int j = 0; j < height; ++j)
    for (int i = 0; i < width; ++i)
      for (size_t k : overlapping(triangles, pixel_square(image, i, j)))
        sets[frame.index(i, j)].push_back(triangles.refs[k]);
  exact_frame_colours(
      scene, frame,
      [&](int i, int j) { return std::span<const TriangleRef>(sets[frame.index(i, j)]); }, 2,
      SameTriangleRef{}, stats);
  return frame.color;
}

/// The nearest of `candidates` pierced by the ray d (Moller-Trumbore), or -1.
inline long nearest(const SceneTriangles& triangles, const std::vector<size_t>& candidates,
                    const Vec3& d) {
  long best = -1;
  double best_t = kInfinity;
  for (size_t k : candidates) {
    const TriangleAtInstant& tri = triangles.at[k];
    const Vec3 e1 = tri.p1 - tri.p0, e2 = tri.p2 - tri.p0, pvec = d.cross(e2);
    const double det = e1.dot(pvec);
    if (det == 0) continue;
    const Vec3 tvec = -tri.p0, qvec = tvec.cross(e1);
    const double u = tvec.dot(pvec) / det, v = d.dot(qvec) / det, t = e2.dot(qvec) / det;
    if (u < 0 || v < 0 || u + v > 1 || t <= 0 || t >= best_t) continue;
    best_t = t;
    best = long(k);
  }
  return best;
}

/// The mean headlight colour of m x m stratified jittered samples over `square` (box filter).
inline Color sampled_colour(const SceneTriangles& triangles, const std::vector<size_t>& candidates,
                            const PixelSquare& s, int m, std::mt19937& rng) {
  std::uniform_real_distribution<double> jitter(0, 1);
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (int b = 0; b < m; ++b)
    for (int a = 0; a < m; ++a) {
      const Vec3 d(s.x0 + (s.x1 - s.x0) * (a + jitter(rng)) / m,
                   s.y0 + (s.y1 - s.y0) * (b + jitter(rng)) / m, 1.0);
      const long k = nearest(triangles, candidates, d);
      if (k < 0) {
        sum += kBackgroundColor.cast<double>();
        continue;
      }
      const TriangleAtInstant& tri = triangles.at[size_t(k)];
      sum += headlight_color(tri, d, view_direction(d, tri.tan_half_fov)).cast<double>();
    }
  return (sum / (double(m) * m)).cast<float>();
}

/// Root mean square and largest absolute difference over every channel of two images.
struct ImageError {
  double rmse = 0, max = 0;
};
inline ImageError image_error(const std::vector<Color>& a, const std::vector<Color>& b) {
  ImageError e;
  for (size_t p = 0; p < a.size(); ++p)
    for (int c = 0; c < 3; ++c) {
      const double d = double(a[p][c]) - double(b[p][c]);
      e.rmse += d * d;
      e.max = std::max(e.max, std::abs(d));
    }
  e.rmse = std::sqrt(e.rmse / (3.0 * double(a.size())));
  return e;
}

}  // namespace kinray::test
