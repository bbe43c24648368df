#include "renderer/antialiasing/square_visibility.h"

#include <algorithm>
#include <cmath>

namespace kinray {
namespace {

/// Appends to `out` the part of the convex polygon `in` where f >= 0 (Sutherland-Hodgman against
/// one line) and returns its vertex count, 0 when fewer than three vertices are left. `in` must
/// not point into `out`. A vertex on the line is kept once, not doubled by a crossing.
uint32_t clip(std::span<const Vec2> in, const Vec3& f, std::vector<Vec2>& out) {
  const size_t start = out.size();
  if (in.empty()) return 0;
  Vec2 p = in.back();
  double fp = evaluate(f, p);
  for (const Vec2& q : in) {
    const double fq = evaluate(f, q);
    if ((fp > 0 && fq < 0) || (fp < 0 && fq > 0)) out.push_back(p + (q - p) * (fp / (fp - fq)));
    if (fq >= 0) out.push_back(q);
    p = q;
    fp = fq;
  }
  if (out.size() - start < 3) {
    out.resize(start);
    return 0;
  }
  return uint32_t(out.size() - start);
}

/// Shoelace area of a counter-clockwise polygon.
double area(std::span<const Vec2> polygon) {
  double twice = 0;
  for (size_t k = 0, n = polygon.size(); k < n; ++k) {
    const Vec2 &p = polygon[k], &q = polygon[(k + 1) % n];
    twice += p.x() * q.y() - q.x() * p.y();
  }
  return 0.5 * twice;
}

/// The square's corners, counter-clockwise (y points up in the image plane).
std::array<Vec2, 4> corners(const PixelSquare& s) {
  return {Vec2(s.x0, s.y0), Vec2(s.x1, s.y0), Vec2(s.x1, s.y1), Vec2(s.x0, s.y1)};
}

/// Rounding leaves slivers along shared edges; below this share of the square they are dropped.
constexpr double kSliver = 1e-12;

}  // namespace

PixelSquare pixel_square(const PixelRays& image, int i, int j) {
  // PixelRays::x(i) and y(j) with 2i + 1 replaced by the corners' 2i and 2i + 2.
  const double aspect = double(image.width) / double(image.height);
  return {(2.0 * i / image.width - 1.0) * aspect, (2.0 * (i + 1) / image.width - 1.0) * aspect,
          1.0 - 2.0 * (j + 1) / image.height, 1.0 - 2.0 * j / image.height};
}

ImageTriangle image_triangle(const Vec3& p0, const Vec3& p1, const Vec3& p2) {
  ImageTriangle t;
  const Vec3 e01 = p0.cross(p1), e12 = p1.cross(p2), e20 = p2.cross(p0);
  const double det = p0.dot(e12);
  if (!(det != 0) || !std::isfinite(det)) {
    t.edge_on = true;
    return t;
  }
  // (p x q) . d has the sign of det exactly where the ray d is on the triangle's side of the
  // plane through the eye and the edge pq: the three together say the ray (not the line) pierces.
  const double sign = det > 0 ? 1.0 : -1.0;
  t.edges = {sign * e01, sign * e12, sign * e20};
  // The plane's normal is e01 + e12 + e20 and its offset from the eye det: the hit of d is at
  // depth z = det / (n . d) (plane_depth.h), so 1 / z is n / det applied to d.
  t.inverse_depth = (e01 + e12 + e20) / det;
  return t;
}

double covered_area(const PixelSquare& square, const ImageTriangle& triangle) {
  if (triangle.edge_on) return 0;
  const std::array<Vec2, 4> c = corners(square);
  std::vector<Vec2> a(c.begin(), c.end()), b;
  for (const Vec3& edge : triangle.edges) {
    b.clear();
    if (clip(a, edge, b) == 0) return 0;
    std::swap(a, b);
  }
  return area(a);
}

void SquareVisibility::resolve(const PixelSquare& square,
                               std::span<const ImageTriangle> triangles) {
  m_square = square;
  m_covered_by_one = false;
  m_pieces.clear();
  m_vertices.clear();
  m_regions.assign(triangles.size(), Region{});
  m_region_vertices.clear();
  const std::array<Vec2, 4> square_corners = corners(square);
  const double sliver = kSliver * square.area();

  // Each triangle's region inside the square, with the box and the inverse-depth range there
  // (w is affine: its extremes over a convex polygon are at vertices).
  for (size_t a = 0; a < triangles.size(); ++a) {
    const ImageTriangle& t = triangles[a];
    if (t.edge_on) continue;
    m_work.assign(square_corners.begin(), square_corners.end());
    bool empty = false;
    for (size_t e = 0; e < 3 && !empty; ++e) {
      m_next_work.clear();
      empty = clip(m_work, t.edges[e], m_next_work) == 0;
      std::swap(m_work, m_next_work);
    }
    if (empty || area(m_work) <= sliver) continue;
    Region& r = m_regions[a];
    r.polygon = {uint32_t(m_region_vertices.size()), uint32_t(m_work.size())};
    r.area = area(m_work);
    r.low = r.high = m_work.front();
    r.w_min = r.w_max = evaluate(t.inverse_depth, m_work.front());
    for (const Vec2& v : m_work) {
      r.low = r.low.cwiseMin(v);
      r.high = r.high.cwiseMax(v);
      const double w = evaluate(t.inverse_depth, v);
      r.w_min = std::min(r.w_min, w);
      r.w_max = std::max(r.w_max, w);
    }
    m_region_vertices.insert(m_region_vertices.end(), m_work.begin(), m_work.end());
  }

  // The fast path, a pixel inside one triangle: it covers the square and is nearer than every
  // other triangle everywhere (its least inverse depth beats their greatest).
  for (size_t a = 0; a < triangles.size(); ++a) {
    const Region& r = m_regions[a];
    if (r.polygon.count == 0) continue;
    const bool covers =
        std::all_of(triangles[a].edges.begin(), triangles[a].edges.end(), [&](const Vec3& edge) {
          return std::all_of(square_corners.begin(), square_corners.end(),
                             [&](const Vec2& c) { return evaluate(edge, c) >= 0; });
        });
    if (!covers) continue;
    bool nearest = true;
    for (size_t b = 0; b < triangles.size() && nearest; ++b)
      nearest = b == a || m_regions[b].polygon.count == 0 || r.w_min > m_regions[b].w_max;
    if (!nearest) continue;
    m_covered_by_one = true;
    m_vertices.assign(square_corners.begin(), square_corners.end());
    m_pieces.push_back({uint32_t(a), 0, 4, square.area()});
    return;
  }

  // Occluders nearest first: a hidden triangle's pieces are gone after the first few cuts.
  m_order.clear();
  for (uint32_t b = 0; b < triangles.size(); ++b)
    if (m_regions[b].polygon.count > 0) m_order.push_back(b);
  std::sort(m_order.begin(), m_order.end(),
            [&](uint32_t p, uint32_t q) { return m_regions[p].w_max > m_regions[q].w_max; });
  for (const uint32_t a : m_order) {
    const Region& r = m_regions[a];
    m_work.assign(m_region_vertices.begin() + r.polygon.first,
                  m_region_vertices.begin() + r.polygon.first + r.polygon.count);
    m_current.assign(1, Span{0, r.polygon.count});
    for (size_t k = 0; k < m_order.size() && !m_current.empty(); ++k) {
      const uint32_t b = m_order[k];
      const Region& s = m_regions[b];
      // b behind a wherever either is seen hides nothing of a, nor do those after it.
      if (s.w_max < r.w_min) break;
      // Nor does b when their boxes are apart.
      if (b == a || (s.low.array() > r.high.array()).any() ||
          (s.high.array() < r.low.array()).any())
        continue;
      subtract(a, b, triangles);
    }
    for (const Span& piece : m_current) {
      const std::span<const Vec2> polygon(m_work.data() + piece.first, piece.count);
      const double piece_area = area(polygon);
      if (piece_area <= sliver) continue;
      m_pieces.push_back({a, uint32_t(m_vertices.size()), piece.count, piece_area});
      m_vertices.insert(m_vertices.end(), polygon.begin(), polygon.end());
    }
  }
}

void SquareVisibility::subtract(uint32_t a, uint32_t b, std::span<const ImageTriangle> triangles) {
  const Region &r = m_regions[a], &s = m_regions[b];
  // The cutter: b's region where b is nearer, b's three edges and the line of equal depth (not
  // needed where b is nearer throughout, so an occluder does not cut a along a useless line).
  std::array<Vec3, 4> cutter = {triangles[b].edges[0], triangles[b].edges[1], triangles[b].edges[2],
                                Vec3::Zero()};
  size_t lines = 3;
  if (!(s.w_min > r.w_max)) {
    const Vec3 nearer = triangles[b].inverse_depth - triangles[a].inverse_depth;
    if (nearer != Vec3::Zero())
      cutter[lines++] = nearer;
    else if (b > a)  // one plane: the earlier triangle is the nearer
      return;
  }
  const double sliver = kSliver * m_square.area();
  m_next.clear();
  m_next_work.clear();
  for (const Span& piece : m_current) {
    const std::span<const Vec2> polygon(m_work.data() + piece.first, piece.count);
    // Wholly outside one of the cutter's lines: untouched (and not cut into needless pieces).
    // Wholly inside all of them: hidden.
    bool outside = false, inside = true;
    for (size_t k = 0; k < lines && !outside; ++k) {
      double low = kInfinity, high = -kInfinity;
      for (const Vec2& v : polygon) {
        const double f = evaluate(cutter[k], v);
        low = std::min(low, f);
        high = std::max(high, f);
      }
      outside = high <= 0;
      inside = inside && low >= 0;
    }
    if (inside && !outside) continue;
    if (outside) {
      m_next.push_back({uint32_t(m_next_work.size()), piece.count});
      m_next_work.insert(m_next_work.end(), polygon.begin(), polygon.end());
      continue;
    }
    // Peel off the part outside each line in turn; what is inside all of them is hidden.
    m_scratch.assign(polygon.begin(), polygon.end());
    for (size_t k = 0; k < lines && !m_scratch.empty(); ++k) {
      const uint32_t first = uint32_t(m_next_work.size());
      const uint32_t count = clip(m_scratch, -cutter[k], m_next_work);
      if (count > 0) {
        if (area(std::span<const Vec2>(m_next_work.data() + first, count)) > sliver)
          m_next.push_back({first, count});
        else
          m_next_work.resize(first);
      }
      m_scratch_rest.clear();
      clip(m_scratch, cutter[k], m_scratch_rest);
      std::swap(m_scratch, m_scratch_rest);
    }
  }
  std::swap(m_current, m_next);
  std::swap(m_work, m_next_work);
}

double SquareVisibility::visible_area(uint32_t owner) const {
  double sum = 0;
  for (const VisiblePiece& piece : m_pieces)
    if (piece.owner == owner) sum += piece.area;
  return sum;
}

double SquareVisibility::background_area() const {
  double sum = 0;
  for (const VisiblePiece& piece : m_pieces) sum += piece.area;
  return std::max(0.0, m_square.area() - sum);
}

}  // namespace kinray
