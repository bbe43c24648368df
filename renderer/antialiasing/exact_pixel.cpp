#include "renderer/antialiasing/exact_pixel.h"

#include <algorithm>
#include <cmath>

namespace kinray {

std::span<const TriangleQuadratureNode, 7> degree5_triangle_rule() {
  static const std::array<TriangleQuadratureNode, 7> rule = [] {
    const double r = std::sqrt(15.0);
    const double a1 = (9 - 2 * r) / 21, b1 = (6 + r) / 21, w1 = (155 + r) / 1200;
    const double a2 = (9 + 2 * r) / 21, b2 = (6 - r) / 21, w2 = (155 - r) / 1200;
    return std::array<TriangleQuadratureNode, 7>{{{1.0 / 3, 1.0 / 3, 1.0 / 3, 9.0 / 40},
                                                  {a1, b1, b1, w1},
                                                  {b1, a1, b1, w1},
                                                  {b1, b1, a1, w1},
                                                  {a2, b2, b2, w2},
                                                  {b2, a2, b2, w2},
                                                  {b2, b2, a2, w2}}};
  }();
  return rule;
}

ExactPixels::ExactPixels(const CameraSpaceScene& scene, const PixelRays& image, double t)
    : ExactPixels(scene, image, t, Config{}) {}

ExactPixels::ExactPixels(const CameraSpaceScene& scene, const PixelRays& image, double t,
                         Config config)
    : m_scene(scene), m_image(image), m_t(t), m_config(config) {
  m_config.textured_subdivision = std::max(1, m_config.textured_subdivision);
  m_config.kink_depth = std::clamp(m_config.kink_depth, 0, 12);
}

namespace {

/// The texture coordinates of the ray d's hit on the plane of a textured `triangle` (the
/// barycentrics of shading.cpp's Moller-Trumbore, without its clamping).
Eigen::Vector2d texture_uv(const TriangleAtInstant& triangle, const Vec2& p) {
  const Vec3 d(p.x(), p.y(), 1.0);
  const Vec3 pvec = d.cross(triangle.e2);
  const double det = triangle.e1.dot(pvec);
  if (!(std::abs(det) > 0)) return Eigen::Vector2d::Zero();
  const double u = (-triangle.p0).dot(pvec) / det, v = d.dot(triangle.qvec) / det;
  const std::vector<Vec2f>& uvs = triangle.source->uvs;
  return ((1 - u - v) * uvs[triangle.vertices[0]].cast<double>() +
          u * uvs[triangle.vertices[1]].cast<double>() +
          v * uvs[triangle.vertices[2]].cast<double>());
}

/// The sub-triangles per side a textured fan triangle (a, b, c) needs: at least `least`, and
/// enough that each spans about half a texel (so the rule sees the bilinear texels' kinks only
/// within a node's reach), at most kMaxTexturedSubdivision.
int textured_subdivision(const TriangleAtInstant& triangle, const Vec2& a, const Vec2& b,
                         const Vec2& c, int least) {
  constexpr int kMaxTexturedSubdivision = 64;
  const Eigen::Vector2d size(triangle.texture->width, triangle.texture->height);
  const Eigen::Vector2d ua = texture_uv(triangle, a), ub = texture_uv(triangle, b),
                        uc = texture_uv(triangle, c);
  const double texels = std::max({((ub - ua).cwiseProduct(size)).cwiseAbs().maxCoeff(),
                                  ((uc - ua).cwiseProduct(size)).cwiseAbs().maxCoeff(),
                                  ((uc - ub).cwiseProduct(size)).cwiseAbs().maxCoeff()});
  if (!std::isfinite(texels)) return kMaxTexturedSubdivision;
  return std::clamp(int(std::ceil(2 * texels)), least, kMaxTexturedSubdivision);
}

/// The interpolated (unnormalised) normal of the ray d's hit on `triangle` dotted with the view
/// direction: the two-sided headlight shades |cos|, whose kink lies where this changes sign (a
/// triangle whose vertex normals straddle the view, as smoothed normals do across a sharp edge).
double facing(const TriangleAtInstant& triangle, const Vec3& d) {
  const Vec3 pvec = d.cross(triangle.e2);
  const double det = triangle.e1.dot(pvec);
  if (!(std::abs(det) > 0)) return 1;
  const double u = (-triangle.p0).dot(pvec) / det, v = d.dot(triangle.qvec) / det;
  const Vec3 n = (1 - u - v) * triangle.normals[0].cast<double>() +
                 u * triangle.normals[1].cast<double>() + v * triangle.normals[2].cast<double>();
  return n.dot(unfold(d, triangle.tan_half_fov));
}

/// Appends to `out` the part of the triangle (p[0], p[1], p[2]) where the affine function with
/// values f[k] at its corners has the sign `side` (a triangle or a quadrilateral, or nothing).
void clip_by_values(const std::array<Vec2, 3>& p, const std::array<double, 3>& f, double side,
                    std::vector<Vec2>& out) {
  out.clear();
  for (size_t k = 0; k < 3; ++k) {
    const size_t n = (k + 1) % 3;
    const double a = side * f[k], b = side * f[n];
    if (a >= 0) out.push_back(p[k]);
    if ((a > 0 && b < 0) || (a < 0 && b > 0)) out.push_back(p[k] + (p[n] - p[k]) * (a / (a - b)));
  }
}

}  // namespace

template <class Shade, class Kink>
Eigen::Vector3d ExactPixels::integrate(std::span<const Vec2> piece,
                                       const TriangleAtInstant* textured, Shade&& shade,
                                       Kink&& kink) {
  const std::span<const TriangleQuadratureNode, 7> rule = degree5_triangle_rule();
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  auto smooth = [&](const Vec2& a, const Vec2& b, const Vec2& c) {
    const Vec2 ab = b - a, ac = c - a;
    const double area = 0.5 * (ab.x() * ac.y() - ab.y() * ac.x());
    if (!(area > 0)) return;
    m_stats.nodes += rule.size();
    for (const TriangleQuadratureNode& node : rule) {
      const Vec2 p = node.l0 * a + node.l1 * b + node.l2 * c;
      sum += (node.weight * area) * shade(Vec3(p.x(), p.y(), 1.0)).template cast<double>();
    }
  };
  auto kink_at = [&](const Vec2& p) { return kink(Vec3(p.x(), p.y(), 1.0)); };
  // The rule on a triangle, unless kink(d) changes sign over its corners and nodes (the integrand
  // is not smooth there, and a polynomial rule converges slowly): then its four midpoint
  // children, to kink_depth halvings, so that only the triangles along the kink are cut; a last
  // one the kink still crosses is cut along the line where the linear interpolant of kink(d)
  // between its corners vanishes (the kink is a conic: straight to second order at that size),
  // and each side gets the rule.
  auto triangle = [&](auto&& self, const Vec2& a, const Vec2& b, const Vec2& c, int depth) -> void {
    const std::array<double, 3> f = {kink_at(a), kink_at(b), kink_at(c)};
    bool positive = f[0] > 0 || f[1] > 0 || f[2] > 0;
    bool negative = f[0] < 0 || f[1] < 0 || f[2] < 0;
    if (depth < m_config.kink_depth)
      for (const TriangleQuadratureNode& node : rule) {
        const double g = kink_at(node.l0 * a + node.l1 * b + node.l2 * c);
        positive = positive || g > 0;
        negative = negative || g < 0;
      }
    if (!positive || !negative) return smooth(a, b, c);
    if (depth < m_config.kink_depth) {
      const Vec2 mab = (a + b) / 2, mbc = (b + c) / 2, mca = (c + a) / 2;
      self(self, a, mab, mca, depth + 1);
      self(self, mab, b, mbc, depth + 1);
      self(self, mca, mbc, c, depth + 1);
      self(self, mbc, mca, mab, depth + 1);
      return;
    }
    for (const double side : {1.0, -1.0}) {
      clip_by_values({a, b, c}, f, side, m_kink_side);
      for (size_t k = 1; k + 1 < m_kink_side.size(); ++k)
        smooth(m_kink_side[0], m_kink_side[k], m_kink_side[k + 1]);
    }
  };
  for (size_t k = 1; k + 1 < piece.size(); ++k) {
    const Vec2 &a = piece[0], &b = piece[k], &c = piece[k + 1];
    const int m =
        textured ? textured_subdivision(*textured, a, b, c, m_config.textured_subdivision) : 1;
    if (m == 1) {
      triangle(triangle, a, b, c, 0);
      continue;
    }
    // m x m congruent sub-triangles on the barycentric grid of step 1 / m.
    const Vec2 u = (b - a) / m, v = (c - a) / m;
    auto grid = [&](int s, int t) { return Vec2(a + double(s) * u + double(t) * v); };
    for (int s = 0; s < m; ++s)
      for (int t = 0; s + t < m; ++t) {
        triangle(triangle, grid(s, t), grid(s + 1, t), grid(s, t + 1), 0);
        if (s + t + 2 <= m)
          triangle(triangle, grid(s + 1, t), grid(s + 1, t + 1), grid(s, t + 1), 0);
      }
  }
  return sum;
}

Color ExactPixels::colour(int i, int j, std::span<const TriangleRef> overlapping) {
  m_refs.assign(overlapping.begin(), overlapping.end());
  return colour_of_refs(i, j);
}

Color ExactPixels::colour_of_refs(int i, int j) {
  std::erase_if(m_refs,
                [&](const TriangleRef& ref) { return !m_scene.objects[ref.object].visible(m_t); });
  // A fixed order whatever the caller's: it breaks the ties of coplanar triangles.
  std::sort(m_refs.begin(), m_refs.end());
  m_refs.erase(std::unique(m_refs.begin(), m_refs.end()), m_refs.end());
  m_at_instant.clear();
  m_image_triangles.clear();
  uint32_t object = kNoHit;
  ShadingInstant instant;
  for (const TriangleRef& ref : m_refs) {
    if (ref.object != object) {
      object = ref.object;
      instant = shading_instant(m_scene, object, m_t);
    }
    const TriangleAtInstant& t =
        m_at_instant.emplace_back(triangle_at_instant(m_scene, ref.object, ref.prim, instant));
    m_image_triangles.push_back(image_triangle(t.p0, t.p1, t.p2));
  }

  const PixelSquare square = pixel_square(m_image, i, j);
  m_visibility.resolve(square, m_image_triangles);
  ++m_stats.pixels;
  m_stats.covered_by_one += m_visibility.covered_by_one();
  m_stats.triangles += m_refs.size();
  m_stats.pieces += m_visibility.pieces().size();
  if (m_visibility.pieces().empty()) return kBackgroundColor;
  Eigen::Vector3d sum = m_visibility.background_area() * kBackgroundColor.cast<double>();
  for (const VisiblePiece& piece : m_visibility.pieces()) {
    const TriangleAtInstant& triangle = m_at_instant[piece.owner];
    // The headlight, as shade_frame shades a centre ray; a lit read-out passes another shade.
    const TriangleAtInstant* textured = triangle.texture != nullptr ? &triangle : nullptr;
    sum += integrate(
        m_visibility.vertices(piece), textured,
        [&](const Vec3& d) {
          return headlight_color(triangle, d, view_direction(d, triangle.tan_half_fov));
        },
        [&](const Vec3& d) { return facing(triangle, d); });
  }
  return (sum / square.area()).cast<float>();
}

Color exact_pixel_colour(const CameraSpaceScene& scene, const PixelRays& image, int i, int j,
                         double t, std::span<const TriangleRef> overlapping) {
  ExactPixels pixels(scene, image, t);
  return pixels.colour(i, j, overlapping);
}

}  // namespace kinray
