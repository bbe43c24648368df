#pragma once
// What a backend produces for one frame: per pixel the object and primitive hit by the centre
// ray, its depth (the ray parameter, = camera-space z), and the shaded colour.
#include <cstdint>
#include <limits>
#include <vector>

#include "scenes/scene.h"

namespace kinray {

inline constexpr uint32_t kNoHit = std::numeric_limits<uint32_t>::max();

struct Frame {
  int width = 0, height = 0;
  double time = 0;
  std::vector<uint32_t> object;  ///< object index, kNoHit for background; row-major, row 0 at top
  std::vector<uint32_t> prim;    ///< triangle index within the object
  std::vector<float> depth;      ///< +inf for background
  std::vector<Color> color;      ///< linear RGB
  /// Per pixel, bit l set when light l reaches the hit (renderer/shadows/lighting.h); empty when the
  /// scene has no lights (the headlight casts no shadows).
  std::vector<uint32_t> lit;

  void resize(int w, int h) {
    width = w;
    height = h;
    const size_t n = size_t(w) * size_t(h);
    object.assign(n, kNoHit);
    prim.assign(n, kNoHit);
    depth.assign(n, std::numeric_limits<float>::infinity());
    color.assign(n, Color::Zero());
    lit.clear();
  }
  [[nodiscard]] size_t pixel_count() const { return object.size(); }
  [[nodiscard]] size_t index(int i, int j) const { return size_t(j) * size_t(width) + size_t(i); }
};

}  // namespace kinray
