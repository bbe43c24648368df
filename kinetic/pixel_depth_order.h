#pragma once
// Per-pixel depth order (DESIGN.md, "Depth order: kinetic sorting per pixel"). Along the centre
// ray d of a pixel the depth of triangle A is z_A = N_A / D_A with N_A = det(v0, v1, v2) (cubic)
// and D_A = (e1 x e2) . d (quadratic), so "A before B" holds while
//     sign(D_A D_B) (N_B D_A - N_A D_B) > 0,
// a degree-5 certificate. While both cover the pixel D does not vanish (it has the sign of O by
// the sign rule), so sign(D_A D_B), taken just after now, is constant. The certificate is exactly antisymmetric
// in (A, B), its origin is the later of the two segment starts and it ends at the earlier of the
// two next flightplan updates, as the kinetic sorts of kinetic_sort.h require; exact ties
// (identical triangles) give the zero polynomial and are broken by triangle id there.
#include <array>
#include <cstdint>
#include <vector>

#include "kinetic/band_motion.h"
#include "kinetic/grid_scene.h"
#include "kinetic/kinetic_sort.h"
#include "kinetic/triangle_motion.h"

namespace kinray {

/// The depth keys of one pixel: ids are global triangle ids (kinetic_sort.h's Keys concept).
class PixelDepthKeys {
 public:
  PixelDepthKeys(const BandMotion* source, int column, int row)
      : m_source(source), m_column(column), m_row(row) {}

  [[nodiscard]] OrderCertificate order_certificate(uint32_t a, uint32_t b, double now) const {
    const MeshSegment& sa = m_source->segment_of(a);
    const MeshSegment& sb = m_source->segment_of(b);
    OrderCertificate c;
    c.origin = std::max(sa.origin, sb.origin);
    c.end = std::min(sa.end, sb.end);
    // Copies: the memo may recycle the first entry while computing the second.
    const DepthPolynomials pa = m_source->depth(a, m_column, m_row, c.origin);
    const DepthPolynomials& pb = m_source->depth(b, m_column, m_row, c.origin);
    const double s = now - c.origin;
    const int sigma = sign_after(pa.denominator, s) * sign_after(pb.denominator, s);
    if (sigma == 0) return c;  // D vanishes only for a triangle that covers nothing: by id
    c.f = pb.numerator * pa.denominator - pa.numerator * pb.denominator;
    if (sigma < 0) c.f = -c.f;
    return c;
  }

  /// Camera-space depth of triangle a along this pixel's ray at t (for audits).
  [[nodiscard]] double value(uint32_t a, double t) const {
    const MeshSegment& sa = m_source->segment_of(a);
    const DepthPolynomials& p = m_source->depth(a, m_column, m_row, sa.origin);
    const double s = t - sa.origin;
    return p.numerator(s) / p.denominator(s);
  }

  [[nodiscard]] int column() const { return m_column; }
  [[nodiscard]] int row() const { return m_row; }

 private:
  const BandMotion* m_source;
  int32_t m_column, m_row;
};

static_assert(KineticKeys<PixelDepthKeys>);

}  // namespace kinray
