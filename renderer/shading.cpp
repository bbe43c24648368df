#include "renderer/shading.h"

#include <algorithm>
#include <cmath>

#include "renderer/shade_rows.h"
#include "util/check.h"

namespace kinray {

ShadingInstant shading_instant(const CameraSpaceScene& scene, uint32_t object, double t) {
  return {locate(scene.objects[object].key_times, t), scene.tan_half_fov(t)};
}

const Texture* shading_texture(const Scene& scene, const Object& object) {
  const Material& material = scene.materials[object.material];
  return material.texture >= 0 && !object.uvs.empty() ? &scene.textures[size_t(material.texture)]
                                                      : nullptr;
}

TriangleOverSegment::TriangleOverSegment(const CameraSpaceScene& scene, uint32_t object,
                                         uint32_t prim, size_t k)
    : m_object(object), m_prim(prim), m_k(k) {
  const CameraSpaceObject& cs = scene.objects[object];
  const Object& source = scene.scene->objects[object];
  const Triangle& tri = source.triangles[prim];
  // CameraSpaceObject::position and normal: a + alpha (b - a) between keys k and k + 1, the key
  // positions themselves for an object without keys to blend.
  m_moving = cs.key_times.size() >= 2;
  const size_t n = cs.vertex_count;
  for (size_t v = 0; v < 3; ++v) {
    m_vertices[v] = tri[v];
    if (!m_moving) {
      m_start[v] = cs.positions[tri[v]];
      m_normal_start[v] = cs.normals[tri[v]];
      continue;
    }
    const Vec3 &a = cs.positions[k * n + tri[v]], &b = cs.positions[(k + 1) * n + tri[v]];
    m_start[v] = a;
    m_step[v] = b - a;
    const Eigen::Vector3f &na = cs.normals[k * n + tri[v]], &nb = cs.normals[(k + 1) * n + tri[v]];
    m_normal_start[v] = na;
    m_normal_step[v] = nb - na;
  }
  m_source = &source;
  const Material& material = scene.scene->materials[source.material];
  m_base = material.base_color;
  m_texture = shading_texture(*scene.scene, source);
}

TriangleAtInstant TriangleOverSegment::at(const ShadingInstant& instant) const {
  KINRAY_DCHECK(!m_moving || instant.segment.k == m_k);
  TriangleAtInstant t;
  t.vertices = m_vertices;
  if (m_moving) {
    const double alpha = instant.segment.alpha;
    t.p0 = m_start[0] + alpha * m_step[0];
    t.p1 = m_start[1] + alpha * m_step[1];
    t.p2 = m_start[2] + alpha * m_step[2];
    for (size_t k = 0; k < 3; ++k) t.normals[k] = m_normal_start[k] + float(alpha) * m_normal_step[k];
  } else {
    t.p0 = m_start[0];
    t.p1 = m_start[1];
    t.p2 = m_start[2];
    t.normals = m_normal_start;
  }
  t.e1 = t.p1 - t.p0;
  t.e2 = t.p2 - t.p0;
  const Vec3 tvec = -t.p0;
  t.qvec = tvec.cross(t.e1);
  t.source = m_source;
  t.base = m_base;
  t.texture = m_texture;
  t.tan_half_fov = instant.tan_half_fov;
  return t;
}

TriangleAtInstant triangle_at_instant(const CameraSpaceScene& scene, uint32_t object, uint32_t prim,
                                      const ShadingInstant& instant) {
  return TriangleOverSegment(scene, object, prim, instant.segment.k).at(instant);
}

Eigen::Vector3f view_direction(const Vec3& d, double tan_half_fov) {
  return unfold(d, tan_half_fov).normalized().cast<float>();
}

namespace {

/// The interpolated unit normal and the base colour of the ray d's hit on `triangle`.
/// The barycentric weights of the ray's hit on the triangle's plane (Moller-Trumbore without the
/// bounds test: the backend has decided the hit; the fov folding is linear so they equal the true
/// ones), clamped into the triangle.
std::array<float, 3> hit_weights(const TriangleAtInstant& triangle, const Vec3& d) {
  const Vec3 pvec = d.cross(triangle.e2);
  const double det = triangle.e1.dot(pvec);
  double u = 1.0 / 3.0, v = 1.0 / 3.0;
  if (std::abs(det) > 0) {
    const Vec3 tvec = -triangle.p0;
    u = std::clamp(tvec.dot(pvec) / det, 0.0, 1.0);
    v = std::clamp(d.dot(triangle.qvec) / det, 0.0, 1.0 - u);
  }
  return {float(1.0 - u - v), float(u), float(v)};
}

Vec2f weighted_uv(const TriangleAtInstant& triangle, const std::array<float, 3>& w) {
  const std::vector<Vec2f>& uvs = triangle.source->uvs;
  return w[0] * uvs[triangle.vertices[0]] + w[1] * uvs[triangle.vertices[1]] +
         w[2] * uvs[triangle.vertices[2]];
}

void normal_and_base(const TriangleAtInstant& triangle, const Vec3& d, Eigen::Vector3f& normal,
                     Color& base) {
  const std::array<float, 3> w = hit_weights(triangle, d);
  Eigen::Vector3f n =
      w[0] * triangle.normals[0] + w[1] * triangle.normals[1] + w[2] * triangle.normals[2];
  const float length = n.norm();
  normal = length > 0 ? Eigen::Vector3f(n / length) : Eigen::Vector3f(0, 0, -1);
  base = triangle.base;
  if (triangle.texture != nullptr)
    base = base.cwiseProduct(triangle.texture->sample(weighted_uv(triangle, w)));
}

Color headlight(const Eigen::Vector3f& normal, const Eigen::Vector3f& view, const Color& base) {
  const float lambert = std::abs(normal.dot(view));
  return base * (kAmbient + kDiffuse * lambert);
}

}  // namespace

SurfacePoint surface_point(const TriangleAtInstant& triangle, const Vec3& d,
                           const Eigen::Vector3f& view) {
  SurfacePoint surface;
  surface.ray = d;
  surface.p0 = triangle.p0;
  surface.p1 = triangle.p1;
  surface.p2 = triangle.p2;
  normal_and_base(triangle, d, surface.normal, surface.base);
  surface.tan_half_fov = triangle.tan_half_fov;
  surface.view = view;
  return surface;
}

Vec2f surface_uv(const TriangleAtInstant& triangle, const Vec3& d) {
  return triangle.texture != nullptr ? weighted_uv(triangle, hit_weights(triangle, d))
                                     : Vec2f::Zero();
}

Color headlight_color(const TriangleAtInstant& triangle, const Vec3& d,
                      const Eigen::Vector3f& view) {
  Eigen::Vector3f normal;
  Color base;
  normal_and_base(triangle, d, normal, base);
  return headlight(normal, view, base);
}

SurfacePoint surface_point(const CameraSpaceScene& scene, const PixelRays& image, int i, int j,
                           uint32_t object, uint32_t prim, const ShadingInstant& instant) {
  const Vec3 d = image.direction(i, j);
  return surface_point(triangle_at_instant(scene, object, prim, instant), d,
                       view_direction(d, instant.tan_half_fov));
}

Color headlight_color(const SurfacePoint& surface) {
  return headlight(surface.normal, surface.view, surface.base);
}

Color shade_hit(const CameraSpaceScene& scene, const PixelRays& image, int i, int j,
                uint32_t object, uint32_t prim, double t) {
  return shade_hit(scene, image, i, j, object, prim, shading_instant(scene, object, t));
}

Color shade_hit(const CameraSpaceScene& scene, const PixelRays& image, int i, int j,
                uint32_t object, uint32_t prim, const ShadingInstant& instant) {
  return headlight_color(surface_point(scene, image, i, j, object, prim, instant));
}

void shade_frame(const CameraSpaceScene& scene, Frame& frame, int threads) {
  struct HeadlightRow {
    Frame& frame;
    void hit(size_t p, const TriangleAtInstant& triangle, const Vec3& d,
             const Eigen::Vector3f& view) {
      frame.color[p] = headlight_color(triangle, d, view);
    }
    void finish() {}
  };
  shade_rows(scene, frame, threads, [&](int) { return HeadlightRow{frame}; });
}

}  // namespace kinray
