#pragma once
// Per-pixel depth order (DESIGN.md, "Depth order: kinetic sorting per pixel"). Along the centre
// ray d of a pixel the depth of triangle A is z_A = N_A / D_A with N_A = det(v0, v1, v2) (cubic)
// and D_A = (e1 x e2) . d (quadratic), so "A before B" holds while
//     sign(D_A D_B) (N_B D_A - N_A D_B) > 0,
// a degree-5 certificate. While both cover the pixel, D has the sign of O = N (the sign rule), so
// sign(D_A D_B) = sign(O_A O_B), taken just after now. The certificate is exactly antisymmetric
// in (A, B), its origin is the later of the two segment starts and it ends at the earlier of the
// two next flightplan updates, as the kinetic sorts of kinetic_sort.h require; exact ties
// (identical triangles) give the zero polynomial and are broken by triangle id there.
#include <cstdint>
#include <vector>

#include "kinetic/grid_scene.h"
#include "kinetic/kinetic_sort.h"
#include "kinetic/triangle_motion.h"

namespace kinray {

/// N and D of one triangle along the ray (x, y, 1), in the local time of its motion.
struct DepthPolynomials {
  Polynomial numerator;    ///< O = det(v0, v1, v2), cubic
  Polynomial denominator;  ///< E_01 + E_12 + E_20 along the ray, quadratic
};
[[nodiscard]] inline DepthPolynomials depth_polynomials(const TriangleMotion& m, double x,
                                                        double y) {
  DepthPolynomials p;
  p.numerator = m.orientation();
  p.denominator = (m.edge(0).along(x, y) + m.edge(1).along(x, y)) + m.edge(2).along(x, y);
  return p;
}

/// What the per-pixel keys of one band read: the scene and the segment each mesh is on there.
struct DepthSource {
  const GridScene* scene = nullptr;
  const std::vector<MeshSegment>* segments = nullptr;  ///< per mesh, the band's current ones
};

/// The depth keys of one pixel: ids are global triangle ids (kinetic_sort.h's Keys concept).
class PixelDepthKeys {
 public:
  PixelDepthKeys(const DepthSource* source, int column, int row)
      : m_source(source), m_column(column), m_row(row) {}

  [[nodiscard]] OrderCertificate order_certificate(uint32_t a, uint32_t b, double now) const {
    const GridScene& scene = *m_source->scene;
    const MeshSegment& sa = (*m_source->segments)[scene.mesh_of_triangle(a)];
    const MeshSegment& sb = (*m_source->segments)[scene.mesh_of_triangle(b)];
    OrderCertificate c;
    c.origin = std::max(sa.origin, sb.origin);
    c.end = std::min(sa.end, sb.end);
    const double x = scene.column_x(m_column), y = scene.row_y(m_row);
    const DepthPolynomials pa =
        depth_polynomials(scene.triangle_motion(a, sa).rebased(c.origin - sa.origin), x, y);
    const DepthPolynomials pb =
        depth_polynomials(scene.triangle_motion(b, sb).rebased(c.origin - sb.origin), x, y);
    const double s = now - c.origin;
    const int sigma = sign_after(pa.numerator, s) * sign_after(pb.numerator, s);
    if (sigma == 0) return c;  // an edge-on triangle covers nothing: a tie, broken by id
    c.f = pb.numerator * pa.denominator - pa.numerator * pb.denominator;
    if (sigma < 0) c.f = -c.f;
    return c;
  }

  /// Camera-space depth of triangle a along this pixel's ray at t (for audits).
  [[nodiscard]] double value(uint32_t a, double t) const {
    const GridScene& scene = *m_source->scene;
    const MeshSegment& sa = (*m_source->segments)[scene.mesh_of_triangle(a)];
    const DepthPolynomials p =
        depth_polynomials(scene.triangle_motion(a, sa), scene.column_x(m_column), scene.row_y(m_row));
    const double s = t - sa.origin;
    return p.numerator(s) / p.denominator(s);
  }

  [[nodiscard]] int column() const { return m_column; }
  [[nodiscard]] int row() const { return m_row; }

 private:
  const DepthSource* m_source;
  int32_t m_column, m_row;
};

static_assert(KineticKeys<PixelDepthKeys>);

}  // namespace kinray
