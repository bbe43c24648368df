#pragma once
// Exact antialiasing (docs/design.md, "Exact antialiasing: the pixel's square as the frustum"):
// the hidden-surface resolution inside one pixel's square (Catmull 1978). Everything happens in
// the image plane z = 1 of camera space, where the ray through (x, y) is d = (x, y, 1):
//  - a triangle's image region R = {(x, y): the ray d pierces it} is the intersection of the
//    three half-planes sign((p x q) . d) = sign(det(v0, v1, v2)) of its edges pq, the centre
//    grid's sign rule, so triangles behind or straddling the eye need no clipping;
//  - its inverse depth along d, w = 1 / z = (n . d) / det(v0, v1, v2) with n the (unnormalised)
//    plane normal, is affine in (x, y) and positive inside R, so "A is nearer than B" is the
//    half-plane w_A > w_B: an interpenetrating pair is split along the line where their depths
//    are equal.
// A triangle's visible region is its region inside the square minus, for every other triangle B,
// B's region where B is nearer: convex pieces, found by cutting convex polygons by lines only.
// Pieces of all triangles and the background tile the square.
#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "scenes/scene.h"
#include "util/pixel_rays.h"

namespace kinray {

/// A point of the image plane z = 1.
using Vec2 = Eigen::Vector2d;

/// A triangle of the scene: object index and triangle index within it.
struct TriangleRef {
  uint32_t object = 0, prim = 0;
  friend bool operator==(const TriangleRef&, const TriangleRef&) = default;
  friend bool operator<(const TriangleRef& a, const TriangleRef& b) {
    return a.object != b.object ? a.object < b.object : a.prim < b.prim;
  }
};

/// The square of a pixel in the image plane: [x0, x1] x [y0, y1].
struct PixelSquare {
  double x0 = 0, x1 = 0, y0 = 0, y1 = 0;
  [[nodiscard]] double area() const { return (x1 - x0) * (y1 - y0); }
};

/// The square of pixel (i, j): centred on (x(i), y(j)), one pixel spacing wide and high. Its
/// corners are computed from the corner lattice, so neighbouring squares share their edges bit
/// for bit (no gap nor overlap between pixels).
[[nodiscard]] PixelSquare pixel_square(const PixelRays& image, int i, int j);

/// An affine function f(x, y) = f[0] x + f[1] y + f[2] of the image plane, f . (x, y, 1).
[[nodiscard]] inline double evaluate(const Vec3& f, const Vec2& p) {
  return f[0] * p.x() + f[1] * p.y() + f[2];
}

/// A triangle as the square sees it: its image region and its inverse depth.
struct ImageTriangle {
  std::array<Vec3, 3> edges;          ///< R = {all three edges(x, y) >= 0}
  Vec3 inverse_depth = Vec3::Zero();  ///< w = 1 / z along (x, y, 1); > 0 inside R
  bool edge_on = false;               ///< det(v0, v1, v2) = 0: its plane holds the eye, no area
};

/// The ImageTriangle of the camera-space triangle (p0, p1, p2).
[[nodiscard]] ImageTriangle image_triangle(const Vec3& p0, const Vec3& p1, const Vec3& p2);

/// The area of the part of `square` whose rays pierce `triangle` (0 when they miss it).
[[nodiscard]] double covered_area(const PixelSquare& square, const ImageTriangle& triangle);

/// One visible convex piece of a triangle: `count` vertices from `first` in
/// SquareVisibility::vertices(), in counter-clockwise order.
struct VisiblePiece {
  uint32_t owner = 0;  ///< the triangle's index in the span given to resolve()
  uint32_t first = 0, count = 0;
  double area = 0;
};

/// The visible pieces of a set of triangles inside one square. Holds its buffers between calls:
/// keep one per thread (or row) and the read-out allocates nothing once they have grown.
class SquareVisibility {
 public:
  /// Resolves which triangle is nearest over every point of `square`. Two triangles in the same
  /// plane (equal depth everywhere) are ordered by their index in `triangles`, the earlier one
  /// nearer. Pieces thinner than rounding (area below 1e-12 of the square) are dropped.
  void resolve(const PixelSquare& square, std::span<const ImageTriangle> triangles);

  [[nodiscard]] std::span<const VisiblePiece> pieces() const { return m_pieces; }
  [[nodiscard]] std::span<const Vec2> vertices(const VisiblePiece& piece) const {
    return {m_vertices.data() + piece.first, piece.count};
  }
  /// The visible area of triangle `owner` (the sum of its pieces).
  [[nodiscard]] double visible_area(uint32_t owner) const;
  /// The area where no triangle is seen: the square's less every piece's.
  [[nodiscard]] double background_area() const;
  /// Whether the last resolve() took the fast path: one triangle covers the square and is
  /// nearer than every other one everywhere in it.
  [[nodiscard]] bool covered_by_one() const { return m_covered_by_one; }

 private:
  /// A polygon of a pool: `count` vertices from `first`.
  struct Span {
    uint32_t first = 0, count = 0;
  };
  /// A triangle's region inside the square, and the bounds of its box and inverse depth there.
  struct Region {
    Span polygon;
    double area = 0;
    Vec2 low = Vec2::Zero(), high = Vec2::Zero();
    double w_min = 0, w_max = 0;
  };

  /// Triangle a's pieces less the part of region b where b is nearer, from m_current to m_next.
  void subtract(uint32_t a, uint32_t b, std::span<const ImageTriangle> triangles);

  PixelSquare m_square;
  bool m_covered_by_one = false;
  std::vector<Region> m_regions;
  std::vector<uint32_t> m_order;  ///< the triangles with a region, nearest w_max first
  std::vector<Vec2> m_region_vertices;
  std::vector<Span> m_current, m_next;  ///< a triangle's pieces being cut, in m_work
  std::vector<Vec2> m_work, m_next_work;
  std::vector<Vec2> m_scratch, m_scratch_rest;  ///< a piece being peeled
  std::vector<VisiblePiece> m_pieces;
  std::vector<Vec2> m_vertices;
};

}  // namespace kinray
