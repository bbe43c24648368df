#pragma once
// The pixel lines of an image: the edges of the pixels' squares, whose crossings are the events of
// the per-square sets. Pixel (i, j) is the square [x_line(i), x_line(i + 1)] x [y_line(j + 1),
// y_line(j)]: its centre is PixelRays' (x(i), y(j)) and its half-sizes are half the spacing of the
// centres. Each line is computed once, here, so that two neighbouring squares share their side
// bit for bit and every user (events, audit, brute force, read-out) sees the same square.
#include <vector>

#include "kinetic/squares/square_overlap.h"
#include "util/pixel_rays.h"

namespace kinray {

class SquareLattice {
 public:
  explicit SquareLattice(const PixelRays& rays) : m_rays(rays) {
    const double aspect = double(rays.width) / double(rays.height);
    // PixelRays' formulas with the half-integer index of the edge: x(i) -/+ half a spacing.
    for (int k = 0; k <= rays.width; ++k) m_x.push_back((2.0 * k / rays.width - 1.0) * aspect);
    for (int k = 0; k <= rays.height; ++k) m_y.push_back(1.0 - 2.0 * k / rays.height);
  }
  [[nodiscard]] const PixelRays& rays() const { return m_rays; }
  [[nodiscard]] int width() const { return m_rays.width; }
  [[nodiscard]] int height() const { return m_rays.height; }
  /// Column line k (0..width), left to right: the left side of column k.
  [[nodiscard]] double x_line(int k) const { return m_x[size_t(k)]; }
  /// Row line k (0..height), top to bottom: the top side of row k (y decreases with k).
  [[nodiscard]] double y_line(int k) const { return m_y[size_t(k)]; }
  /// All column lines, then all row lines, in order (width + 1 and height + 1 of them).
  [[nodiscard]] const double* x_lines() const { return m_x.data(); }
  [[nodiscard]] const double* y_lines() const { return m_y.data(); }
  /// The closed square of pixel (i, j).
  [[nodiscard]] ImageSquare square(int i, int j) const {
    return {m_x[size_t(i)], m_x[size_t(i) + 1], m_y[size_t(j) + 1], m_y[size_t(j)]};
  }

 private:
  PixelRays m_rays;
  std::vector<double> m_x, m_y;
};

}  // namespace kinray
