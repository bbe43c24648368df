#pragma once
// A textured front under the shutter. While a pixel's front is fixed, the hit slides over the
// triangle and its texture coordinates follow a smooth path; the texture along it is not smooth
// (a bilinear texture has a kink at every texel's centre line) and crosses many texels in a
// window (on BART's kitchen most floor pixels cross 16 to 64 at 24 fps), so a quadrature node's
// sample of it aliases. Instead each node shows the mean of the texture over its cell of the
// interval (GaussLegendre::cell_lo, cell_hi): the path's chord over the cell, averaged exactly
// (Texture::path_average). The node's lighting multiplies it: exact where the lighting is constant
// over the cell and the path straight, and the error is the product of the two variations over
// one cell and the path's bend away from its chord.
#include <cstdint>

#include "renderer/shading.h"
#include "scenes/camera_space.h"

namespace kinray {

class TexturePath {
 public:
  /// The front (object, prim) along pixel direction d; `scene` must outlive this.
  TexturePath(const CameraSpaceScene& scene, uint32_t object, uint32_t prim, const Vec3& d);
  /// Whether the front has a texture (else base() is never needed).
  [[nodiscard]] bool textured() const { return m_texture != nullptr; }
  /// The base colour over the cell [lo, hi]: the material's colour times the texture's mean along
  /// the chord of the uv path from lo to hi.
  [[nodiscard]] Color base(double lo, double hi);

 private:
  [[nodiscard]] Vec2f uv_at(double t);

  const CameraSpaceScene& m_scene;
  uint32_t m_object, m_prim;
  Vec3 m_d;
  const Texture* m_texture = nullptr;
  Color m_material;  ///< the material's base colour
  /// The last two uvs computed: adjacent cells share an end.
  double m_t[2] = {kInfinity, kInfinity};
  Vec2f m_uv[2] = {Vec2f::Zero(), Vec2f::Zero()};
  int m_last = 0;
};

}  // namespace kinray
