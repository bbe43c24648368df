#include "renderer/antialiasing/exact_pixel.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

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

std::span<const TriangleQuadratureNode, 3> degree2_triangle_rule() {
  static const std::array<TriangleQuadratureNode, 3> rule{{{2.0 / 3, 1.0 / 6, 1.0 / 6, 1.0 / 3},
                                                           {1.0 / 6, 2.0 / 3, 1.0 / 6, 1.0 / 3},
                                                           {1.0 / 6, 1.0 / 6, 2.0 / 3, 1.0 / 3}}};
  return rule;
}

ExactPixels::ExactPixels(const CameraSpaceScene& scene, const PixelRays& image, double t)
    : ExactPixels(scene, image, t, Config{}) {}

ExactPixels::ExactPixels(const CameraSpaceScene& scene, const PixelRays& image, double t,
                         Config config)
    : ExactPixels(scene, image, t, config, nullptr) {}

ExactPixels::ExactPixels(const CameraSpaceScene& scene, const PixelRays& image, double t,
                         Config config, const ExactLights* lights)
    : m_scene(scene), m_lights(lights), m_image(image), m_t(t), m_config(config) {
  m_config.textured_subdivision = std::max(1, m_config.textured_subdivision);
  m_config.kink_depth = std::clamp(m_config.kink_depth, 0, 12);
  m_config.shadow_area = std::clamp(m_config.shadow_area, 1e-6, 1.0);
  m_config.shadow_bisections = std::clamp(m_config.shadow_bisections, 0, 48);
  if (m_lights != nullptr) {
    if (m_lights->lights == nullptr || m_lights->tracer == nullptr ||
        m_lights->lights->size() > kMaxLights)
      throw std::invalid_argument("ExactPixels: lit read-out needs 1 to 32 lights and a tracer");
    if (m_lights->lights->empty()) m_lights = nullptr;  // the headlight, as shade_frame does
  }
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

/// The affine function of the image plane with values fa, fb, fc at a, b, c (a counter-clockwise
/// triangle of positive area), as f . (x, y, 1).
Vec3 affine_through(const Vec2& a, const Vec2& b, const Vec2& c, double fa, double fb, double fc) {
  const Vec2 ab = b - a, ac = c - a;
  const double det = ab.x() * ac.y() - ab.y() * ac.x();
  const double gx = ((fb - fa) * ac.y() - (fc - fa) * ab.y()) / det;
  const double gy = ((fc - fa) * ab.x() - (fb - fa) * ac.x()) / det;
  return {gx, gy, fa - gx * a.x() - gy * a.y()};
}

/// An affine function of the image plane that vanishes on the line through p and q.
Vec3 line_through(const Vec2& p, const Vec2& q) {
  const Vec2 e = q - p;
  return {-e.y(), e.x(), e.y() * p.x() - e.x() * p.y()};
}

/// Appends to `out` the part of the convex polygon `in` where side * f >= 0 (nothing when fewer
/// than three vertices are left).
void clip_polygon(std::span<const Vec2> in, const Vec3& f, double side, std::vector<Vec2>& out) {
  out.clear();
  for (size_t k = 0; k < in.size(); ++k) {
    const Vec2 &p = in[k], &q = in[(k + 1) % in.size()];
    const double a = side * evaluate(f, p), b = side * evaluate(f, q);
    if (a >= 0) out.push_back(p);
    if ((a > 0 && b < 0) || (a < 0 && b > 0)) out.push_back(p + (q - p) * (a / (a - b)));
  }
  if (out.size() < 3) out.clear();
}

/// Twice the signed area of the triangle (a, b, c).
double twice_area(const Vec2& a, const Vec2& b, const Vec2& c) {
  const Vec2 ab = b - a, ac = c - a;
  return ab.x() * ac.y() - ab.y() * ac.x();
}

/// Calls fan(a, b, c) on each triangle of the fan of the convex `piece`, and on a textured
/// triangle (`textured`, else nullptr) on its m x m congruent sub-triangles of the barycentric
/// grid of step 1 / m instead (textured_subdivision: half-texel pieces).
template <class Fan>
void for_each_fan_triangle(std::span<const Vec2> piece, const TriangleAtInstant* textured,
                           int subdivision, Fan&& fan) {
  for (size_t k = 1; k + 1 < piece.size(); ++k) {
    const Vec2 &a = piece[0], &b = piece[k], &c = piece[k + 1];
    const int m = textured ? textured_subdivision(*textured, a, b, c, subdivision) : 1;
    if (m == 1) {
      fan(a, b, c);
      continue;
    }
    const Vec2 u = (b - a) / m, v = (c - a) / m;
    auto grid = [&](int s, int t) { return Vec2(a + double(s) * u + double(t) * v); };
    for (int s = 0; s < m; ++s)
      for (int t = 0; s + t < m; ++t) {
        fan(grid(s, t), grid(s + 1, t), grid(s, t + 1));
        if (s + t + 2 <= m) fan(grid(s + 1, t), grid(s + 1, t + 1), grid(s, t + 1));
      }
  }
}

}  // namespace

template <class Shade, class Kink>
Eigen::Vector3d ExactPixels::integrate(std::span<const Vec2> piece,
                                       const TriangleAtInstant* textured, Shade&& shade,
                                       Kink&& kink) {
  const std::span<const TriangleQuadratureNode> high = degree5_triangle_rule(),
                                                low = degree2_triangle_rule();
  // Textured pieces keep degree 5: their half-texel sub-triangles straddle the texels' kinks.
  const double low_order_area = textured ? 0.0 : m_config.low_order_area * m_pixel_area;
  // The rule of a triangle of this area (the kink test reads the same nodes).
  auto rule_for = [&](double area) { return area > low_order_area ? high : low; };
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  auto smooth = [&](const Vec2& a, const Vec2& b, const Vec2& c) {
    const double area = 0.5 * twice_area(a, b, c);
    if (!(area > 0)) return;
    const std::span<const TriangleQuadratureNode> rule = rule_for(area);
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
      for (const TriangleQuadratureNode& node : rule_for(0.5 * std::fabs(twice_area(a, b, c)))) {
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
  for_each_fan_triangle(
      piece, textured, m_config.textured_subdivision,
      [&](const Vec2& a, const Vec2& b, const Vec2& c) { triangle(triangle, a, b, c, 0); });
  return sum;
}

void ExactPixels::shade_lit(std::span<const Vec2> points, std::span<LitPoint> out,
                            uint32_t traced) {
  const std::vector<CameraSpaceLight>& lights = *m_lights->lights;
  const TriangleAtInstant& triangle = *m_lit_triangle;
  m_lit_hits.clear();
  m_lit_rays.clear();
  for (size_t k = 0; k < points.size(); ++k) {
    const Vec2& p = points[k];
    const Vec3 d(p.x(), p.y(), 1.0);
    const LitHit& hit =
        m_lit_hits.emplace_back(lit_hit(triangle, d, view_direction(d, triangle.tan_half_fov)));
    LitPoint& point = out[k];
    point.p = p;
    point.faced = 0;
    // lit_color's own terms: the normal turned to the eye where facing > 0, and its cosine with
    // each light (max(0, cos) kinks at the terminator).
    const SurfacePoint& s = hit.surface;
    point.kinks[0] = s.normal.dot(s.view);
    const Eigen::Vector3f n = visible_normal(s);
    for (size_t l = 0; l < lights.size(); ++l) {
      const float cosine = lambert_term(n, s, hit.origin, lights[l]);
      point.kinks[1 + l] = cosine;
      if (!(cosine > 0) || !(traced >> l & 1u)) continue;
      if (const auto ray = shadow_ray(hit, lights[l], m_lit_ref.object, m_lit_ref.prim)) {
        m_lit_rays.push_back(*ray);
        point.faced |= 1u << l;
      }
    }
  }
  // One batch per call: the tree tracer's cost per call (its frame boxes' lock, its ray buffer)
  // is shared by every point's rays.
  m_lit_blocked.assign(m_lit_rays.size(), 0);
  if (!m_lit_rays.empty()) m_lights->tracer->occluded(m_lit_rays, m_lit_blocked);
  m_stats.shadow_rays += m_lit_rays.size();
  size_t r = 0;
  for (size_t k = 0; k < points.size(); ++k) {
    LitPoint& point = out[k];
    point.mask = 0;
    for (size_t l = 0; l < lights.size(); ++l)
      if (point.faced >> l & 1u)
        if (!m_lit_blocked[r++]) point.mask |= 1u << l;
    point.colour = lit_color(m_lit_hits[k], lights, point.mask);
  }
}

double ExactPixels::shade_lit_rule(const Vec2& a, const Vec2& b, const Vec2& c,
                                   std::array<LitPoint, 7>& nodes) {
  const double area = 0.5 * twice_area(a, b, c);
  if (!(area > 0)) return 0;
  const std::span<const TriangleQuadratureNode, 7> rule = degree5_triangle_rule();
  std::array<Vec2, 7> at;
  for (size_t k = 0; k < rule.size(); ++k) at[k] = rule[k].l0 * a + rule[k].l1 * b + rule[k].l2 * c;
  shade_lit(at, nodes);
  return area;
}

void ExactPixels::integrate_lit_rule(const Vec2& a, const Vec2& b, const Vec2& c,
                                     Eigen::Vector3d& sum) {
  std::array<LitPoint, 7> nodes;
  const double area = shade_lit_rule(a, b, c, nodes);
  if (!(area > 0)) return;
  const std::span<const TriangleQuadratureNode, 7> rule = degree5_triangle_rule();
  m_stats.nodes += rule.size();
  for (size_t k = 0; k < rule.size(); ++k)
    sum += (rule[k].weight * area) * nodes[k].colour.cast<double>();
}

// The lit shading is smooth except across three kinds of lines: where the interpolated normal
// turns to face the eye (lit_color flips it: a jump), a light's terminator (a kink of
// max(0, cos)), and a shadow boundary (a jump of the mask). A triangle whose corners and nodes
// agree on all of them takes the rule on the nodes already shaded. Otherwise it is halved, to
// kink_depth for the first two and to shadow_area for the third, so that only the sub-triangles
// along the lines are refined; a last one is cut along the chord of each line it holds and each
// part takes the rule. A kink's chord is where the linear interpolant of its function between
// the corners vanishes (as the headlight's); a shadow boundary has no function to interpolate,
// only masks, so when one corner is lit differently from the other two the boundary's crossings
// of the two edges from that corner are found by bisection (as motion blur bisects a mask's
// change in time, shutter_shadows.h) and the chord joins them. A polygonal occluder's shadow on
// a triangle's plane is straight in the image, so the chord is the boundary up to the
// bisection's step; where a last sub-triangle holds no such pattern (a shadow's corner, a sliver
// between its corners) its nodes' masks stand for it: that area is what is left unresolved.
void ExactPixels::integrate_lit_triangle(const std::array<LitPoint, 3>& corners, int depth,
                                         Eigen::Vector3d& sum) {
  const Vec2 &a = corners[0].p, &b = corners[1].p, &c = corners[2].p;
  std::array<LitPoint, 7> nodes;
  const double area = shade_lit_rule(a, b, c, nodes);
  if (!(area > 0)) return;
  const std::span<const TriangleQuadratureNode, 7> rule = degree5_triangle_rule();

  // Light l's shadow boundary crosses where, of the points it faces, some see it and some not;
  // its terminator matters only where it reaches some point (elsewhere it adds nothing).
  uint32_t reached = 0, blocked = 0;
  auto tally = [&](const LitPoint& point) {
    reached |= point.mask;
    blocked |= point.faced & ~point.mask;
  };
  for (const LitPoint& point : corners) tally(point);
  for (const LitPoint& point : nodes) tally(point);
  const uint32_t boundaries = reached & blocked;
  const bool shadowed = boundaries != 0;
  const size_t functions = 1 + m_lights->lights->size();
  uint64_t crossing = 0;  // bit f: function f changes sign over the corners and nodes
  for (size_t f = 0; f < functions; ++f) {
    if (f > 0 && !(reached >> (f - 1) & 1u)) continue;
    bool positive = false, negative = false;
    auto see = [&](const LitPoint& point) {
      positive = positive || point.kinks[f] > 0;
      negative = negative || point.kinks[f] < 0;
    };
    for (const LitPoint& point : corners) see(point);
    for (const LitPoint& point : nodes) see(point);
    if (positive && negative) crossing |= uint64_t(1) << f;
  }

  if ((crossing != 0 && depth < m_config.kink_depth) ||
      (shadowed && area > m_config.shadow_area * m_pixel_area)) {
    const std::array<Vec2, 3> middle = {(a + b) / 2, (b + c) / 2, (c + a) / 2};
    std::array<LitPoint, 3> m;
    shade_lit(middle, m);
    integrate_lit_triangle({corners[0], m[0], m[2]}, depth + 1, sum);
    integrate_lit_triangle({m[0], corners[1], m[1]}, depth + 1, sum);
    integrate_lit_triangle({m[2], m[1], corners[2]}, depth + 1, sum);
    integrate_lit_triangle({m[1], m[2], m[0]}, depth + 1, sum);
    return;
  }
  auto on_nodes = [&] {
    m_stats.nodes += rule.size();
    for (size_t k = 0; k < rule.size(); ++k)
      sum += (rule[k].weight * area) * nodes[k].colour.cast<double>();
  };
  if (crossing == 0 && !shadowed) return on_nodes();

  // The chords of this last sub-triangle.
  std::array<Vec3, kMaxLitKinks + 1> chords;
  size_t count = 0;
  for (size_t f = 0; f < functions; ++f) {
    if (!(crossing >> f & 1u)) continue;
    const double fa = corners[0].kinks[f], fb = corners[1].kinks[f], fc = corners[2].kinks[f];
    // Only where the corners straddle the line does their interpolant locate it.
    if ((fa > 0 || fb > 0 || fc > 0) && (fa < 0 || fb < 0 || fc < 0))
      chords[count++] = affine_through(a, b, c, fa, fb, fc);
  }
  if (shadowed) {
    // The corners' masks of the lights whose boundary crosses (a terminator is a kink's chord).
    const auto mask = [&](const LitPoint& point) { return point.mask & boundaries; };
    size_t odd = 3;
    for (size_t k = 0; k < 3; ++k)
      if (mask(corners[k]) != mask(corners[(k + 1) % 3]) &&
          mask(corners[k]) != mask(corners[(k + 2) % 3]) &&
          mask(corners[(k + 1) % 3]) == mask(corners[(k + 2) % 3]))
        odd = k;
    if (odd < 3) {
      const uint32_t inside = mask(corners[odd]);
      // Each edge from the odd corner: [near, far] holds the change of mask.
      std::array<Vec2, 2> near = {corners[odd].p, corners[odd].p};
      std::array<Vec2, 2> far = {corners[(odd + 1) % 3].p, corners[(odd + 2) % 3].p};
      std::array<Vec2, 2> middle;
      std::array<LitPoint, 2> probe;
      for (int step = 0; step < m_config.shadow_bisections; ++step) {
        for (size_t e = 0; e < 2; ++e) middle[e] = (near[e] + far[e]) / 2;
        shade_lit(middle, probe, boundaries);
        for (size_t e = 0; e < 2; ++e) (mask(probe[e]) == inside ? near[e] : far[e]) = middle[e];
      }
      chords[count++] = line_through((near[0] + far[0]) / 2, (near[1] + far[1]) / 2);
      ++m_stats.shadow_cuts;
    }
  }
  if (count == 0) return on_nodes();  // unresolved: the nodes' masks stand for the area

  m_cut_pieces.assign(1, std::vector<Vec2>{a, b, c});
  for (size_t k = 0; k < count; ++k) {
    m_cut_next.clear();
    for (const std::vector<Vec2>& polygon : m_cut_pieces)
      for (const double side : {1.0, -1.0}) {
        m_cut_next.emplace_back();
        clip_polygon(polygon, chords[k], side, m_cut_next.back());
        if (m_cut_next.back().empty()) m_cut_next.pop_back();
      }
    std::swap(m_cut_pieces, m_cut_next);
  }
  for (const std::vector<Vec2>& polygon : m_cut_pieces)
    for (size_t k = 1; k + 1 < polygon.size(); ++k)
      integrate_lit_rule(polygon[0], polygon[k], polygon[k + 1], sum);
}

Eigen::Vector3d ExactPixels::integrate_lit(std::span<const Vec2> piece) {
  const TriangleAtInstant& triangle = *m_lit_triangle;
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  std::array<LitPoint, 3> corners;
  for_each_fan_triangle(piece, triangle.texture != nullptr ? &triangle : nullptr,
                        m_config.textured_subdivision,
                        [&](const Vec2& a, const Vec2& b, const Vec2& c) {
                          if (!(twice_area(a, b, c) > 0)) return;
                          const std::array<Vec2, 3> p = {a, b, c};
                          shade_lit(p, corners);
                          integrate_lit_triangle(corners, 0, sum);
                        });
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
  m_pixel_area = square.area();
  m_visibility.resolve(square, m_image_triangles);
  ++m_stats.pixels;
  m_stats.covered_by_one += m_visibility.covered_by_one();
  m_stats.triangles += m_refs.size();
  m_stats.pieces += m_visibility.pieces().size();
  if (m_visibility.pieces().empty()) return kBackgroundColor;
  Eigen::Vector3d sum = m_visibility.background_area() * kBackgroundColor.cast<double>();
  for (const VisiblePiece& piece : m_visibility.pieces()) {
    const TriangleAtInstant& triangle = m_at_instant[piece.owner];
    if (m_lights != nullptr) {
      m_lit_triangle = &triangle;
      m_lit_ref = m_refs[piece.owner];
      sum += integrate_lit(m_visibility.vertices(piece));
      continue;
    }
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
