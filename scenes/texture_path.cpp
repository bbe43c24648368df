// Texture::path_average. In texel coordinates X = u W - 1/2, Y = (1 - v) H - 1/2 (those of
// Texture::sample, without the wrap: texel indices wrap instead, so the bilinear function is
// continuous and periodic), sample() is bilinear inside each cell [i, i + 1] x [j, j + 1]. Along
// a straight segment the cell coordinates are linear in the segment's parameter, so the bilinear
// function is a quadratic there and Simpson's rule integrates it exactly. The segment is cut
// where it crosses a cell's side (an integer X or Y) and each cut piece weighted by its length.
#include <algorithm>
#include <cmath>

#include "scenes/scene.h"

namespace kinray {
namespace {

/// Cells walked at most: a segment crossing more (a texture minified thousands of times under a
/// pixel) is averaged over this many equal pieces by the midpoint rule instead.
constexpr int kMaxCells = 4096;

/// The parameters s in (0, 1) where start + s step crosses an integer, in increasing order.
class LineCrossings {
 public:
  LineCrossings(double start, double step) : m_start(start), m_step(step) {
    if (step > 0) {
      m_c = std::floor(start) + 1;
      m_count = std::max(0.0, std::ceil(start + step) - m_c);
    } else if (step < 0) {
      m_c = std::ceil(start) - 1;
      m_count = std::max(0.0, m_c - std::floor(start + step));
    }
  }
  /// The next crossing's parameter (infinity when there is none left).
  [[nodiscard]] double next() const { return m_count > 0 ? (m_c - m_start) / m_step : kInfinity; }
  void pass() {
    m_c += m_step > 0 ? 1 : -1;
    --m_count;
  }

 private:
  double m_start, m_step;
  double m_c = 0;      ///< the integer crossed next
  double m_count = 0;  ///< crossings left
};

}  // namespace

Color Texture::path_average(Vec2f from, Vec2f to) const {
  if (from == to || width <= 0 || height <= 0) return sample(from);
  // Whole periods of the texture change nothing: the segment starts in the period of [0, 1)^2,
  // so the texel coordinates stay small whatever the uvs.
  const double u0 = double(from.x()), v0 = double(from.y());
  const double x0 = (u0 - std::floor(u0)) * width - 0.5,
               y0 = (1.0 - (v0 - std::floor(v0))) * height - 0.5;
  const double du = double(to.x()) - u0, dv = double(to.y()) - v0;
  const double dx = du * width, dy = -dv * height;
  // sample() at (x, y) of cell (i, j), which holds it up to rounding.
  const auto bilinear = [&](double x, double y, long long i, long long j) {
    return blend(i, j, float(std::clamp(x - double(i), 0.0, 1.0)),
                 float(std::clamp(y - double(j), 0.0, 1.0)));
  };
  const double crossings = std::abs(std::floor(x0 + dx) - std::floor(x0)) +
                           std::abs(std::floor(y0 + dy) - std::floor(y0));
  if (!(crossings < kMaxCells)) {
    Color sum = Color::Zero();
    for (int k = 0; k < kMaxCells; ++k) {
      const double s = (k + 0.5) / kMaxCells;
      sum += sample(Vec2f(float(u0 + s * du), float(v0 + s * dv)));
    }
    return sum / float(kMaxCells);
  }
  // Walk the cells: the next crossing of an integer X and of an integer Y, the nearer first.
  LineCrossings across_x(x0, dx), across_y(y0, dy);
  Color sum = Color::Zero();
  for (double a = 0; a < 1;) {
    const double b = std::min({across_x.next(), across_y.next(), 1.0});
    if (across_x.next() == b) across_x.pass();
    if (across_y.next() == b) across_y.pass();
    if (!(b > a)) continue;
    const double m = (a + b) / 2;
    // The cell of the piece's middle holds the whole piece.
    const auto i = (long long)std::floor(x0 + m * dx), j = (long long)std::floor(y0 + m * dy);
    const Color fa = bilinear(x0 + a * dx, y0 + a * dy, i, j);
    const Color fm = bilinear(x0 + m * dx, y0 + m * dy, i, j);
    const Color fb = bilinear(x0 + b * dx, y0 + b * dy, i, j);
    sum += float((b - a) / 6) * (fa + 4 * fm + fb);
    a = b;
  }
  return sum;
}

}  // namespace kinray
