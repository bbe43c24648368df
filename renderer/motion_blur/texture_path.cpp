#include "renderer/motion_blur/texture_path.h"

namespace kinray {

TexturePath::TexturePath(const CameraSpaceScene& scene, uint32_t object, uint32_t prim,
                         const Vec3& d)
    : m_scene(scene), m_object(object), m_prim(prim), m_d(d) {
  const Object& source = scene.scene->objects[scene.objects[object].object];
  m_texture = shading_texture(*scene.scene, source);
  m_material = scene.scene->materials[source.material].base_color;
}

Vec2f TexturePath::uv_at(double t) {
  for (int k = 0; k < 2; ++k)
    if (m_t[k] == t) return m_uv[k];
  m_last ^= 1;
  m_t[m_last] = t;
  m_uv[m_last] = surface_uv(
      triangle_at_instant(m_scene, m_object, m_prim, shading_instant(m_scene, m_object, t)), m_d);
  return m_uv[m_last];
}

Color TexturePath::base(double lo, double hi) {
  return m_material.cwiseProduct(m_texture->path_average(uv_at(lo), uv_at(hi)));
}

}  // namespace kinray
