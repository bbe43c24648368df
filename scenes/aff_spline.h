#pragma once
// Kochanek-Bartels (tension, continuity, bias) splines of BART's keyframes, evaluated as BART's
// reference code evaluates them (animation.c, kbsplpos.c, kbsplrot.c after Dave Eberly's Magic
// Software): n >= 4 keys give n - 3 cubic pieces between keys 1 .. n-2; the first and the last key
// only shape the end tangents, and the curve is clamped outside [t_1, t_{n-2}]. Rotations are
// axis-angle keys turned into quaternions, each made to lie within 90 degrees of the previous one,
// and interpolated by squad with Kochanek-Bartels tangents taken in the quaternion log space.
#include <Eigen/Geometry>
#include <span>
#include <vector>

namespace kinray {

/// One key: a time, a value (a translation, a scale, or an axis and an angle in degrees), and the
/// tension, continuity and bias that shape the curve through it.
struct SplineKey {
  double time = 0;
  Eigen::Vector3d value = Eigen::Vector3d::Zero();
  double angle_degrees = 0;  ///< rotation keys only
  double tension = 0, continuity = 0, bias = 0;
};

/// A Kochanek-Bartels cubic through 3D points (translations and scales).
class PositionSpline {
 public:
  /// `keys`: at least 4, key i+2 at another time than key i (checked by the parser).
  explicit PositionSpline(std::span<const SplineKey> keys);
  [[nodiscard]] Eigen::Vector3d at(double t) const;
  /// [t_1, t_{n-2}]: where the curve is not clamped.
  [[nodiscard]] double begin() const { return m_pieces.front().t0; }
  [[nodiscard]] double end() const { return m_pieces.back().t1; }

 private:
  struct Piece {
    Eigen::Vector3d c0, c1, c2, c3;  // c0 + u (c1 + u (c2 + u c3)), u in [0, 1]
    double t0 = 0, t1 = 0;
  };
  std::vector<Piece> m_pieces;
};

/// A Kochanek-Bartels squad through rotations.
class RotationSpline {
 public:
  /// `keys` as for PositionSpline; value is the rotation axis (normalized here; a zero axis is the
  /// identity), angle_degrees the angle about it.
  explicit RotationSpline(std::span<const SplineKey> keys);
  [[nodiscard]] Eigen::Quaterniond at(double t) const;

 private:
  struct Piece {
    Eigen::Quaterniond p, a, b, q;  // squad(s; p, a, b, q)
    double t0 = 0, t1 = 0;
  };
  std::vector<Piece> m_pieces;
};

/// Which piece of a clamped spline covers t, and where in it (BART's ComputeIAndU): before the
/// first piece s = 0 on piece 0, after the last s = 1 on the last; pieces of zero length are never
/// chosen inside the range.
struct PieceParameter {
  size_t piece = 0;
  double s = 0;
};
template <class Piece>
[[nodiscard]] PieceParameter locate_piece(const std::vector<Piece>& pieces, double t) {
  if (!(pieces.front().t0 < t)) return {0, 0.0};
  if (!(t < pieces.back().t1)) return {pieces.size() - 1, 1.0};
  size_t i = 0;
  while (i + 1 < pieces.size() && !(t < pieces[i].t1)) ++i;
  const double span = pieces[i].t1 - pieces[i].t0;
  return {i, span == 0 ? 0.0 : (t - pieces[i].t0) / span};
}

}  // namespace kinray
