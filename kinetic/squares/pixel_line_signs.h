#pragma once
// The two families of signs that decide which squares a triangle's region overlaps
// (docs/design.md, "Exact antialiasing"), and how a record locates itself among them:
//   - a vertex against a pixel line: X - x Z (column line x) or Y - y Z (row line y), linear in t
//     on a key segment; read with the vertex's side of the eye plane, it says on which side of the
//     line the vertex's projection lies (also for a vertex behind the eye, whose projection is
//     the projective point (X/Z, Y/Z));
//   - an edge line against a square corner c: the edge function E_pq(c) = (p x q) . c, quadratic.
// Signs are taken just after the time (sign_plus: the zero polynomial reads +), in records,
// events and audit alike, so that a certificate rebuilt at its own event holds just after it.
// Along a family of parallel lines both signs form one step (they are affine in the line's
// coordinate), so a record keeps only where the step is and watches the two lines around it.
#include "kinetic/grid/coverage_rule.h"
#include "kinetic/motion/triangle_motion.h"

namespace kinray {

/// X - c Z (axis 0) or Y - c Z (axis 1) of a moving point, linear in s.
[[nodiscard]] inline Polynomial pixel_line_side(const PointMotion& p, int axis, double c) {
  Polynomial f;
  f.degree = 1;
  f.c[0] = p.a[axis] - c * p.a.z();
  f.c[1] = p.b[axis] - c * p.b.z();
  return f;
}

/// The certificate polynomial whose positive sign means "the projection of p lies after line c":
/// right of a column line (axis 0), below a row line (axis 1, y decreasing down the image).
/// z_sign is the vertex's side of the eye plane (+1 in front): behind it, the projective point's
/// side flips with Z.
[[nodiscard]] inline Polynomial after_line(const PointMotion& p, int axis, double c, int z_sign) {
  const Polynomial f = pixel_line_side(p, axis, c);
  return (axis == 0) == (z_sign > 0) ? f : -f;
}

/// Number of leading indices of [0, n) where pred holds, by bisection, for a predicate that holds
/// on a prefix: the result r has pred(r - 1) (or r = 0) and !pred(r) (or r = n) as evaluated, so
/// that a state read from it agrees with the signs its certificates are built from, even where
/// rounding makes the evaluated signs not quite monotone.
template <class Pred>
[[nodiscard]] int leading_count(int n, Pred&& pred) {
  int lo = -1, hi = n;  // pred(lo) true, pred(hi) false by convention
  while (hi - lo > 1) {
    const int mid = lo + (hi - lo) / 2;
    (pred(mid) ? lo : hi) = mid;
  }
  return hi;
}

/// The cell of p's projection among lines 0..n - 1 of one axis: c when it lies after lines 0..c
/// and before c + 1..n - 1 (-1 before all, n - 1 after all: off the image it stays put).
[[nodiscard]] inline int locate_cell(const PointMotion& p, int axis, int z_sign, int n,
                                     const double* lines, double s) {
  return leading_count(
             n, [&](int k) { return sign_plus(after_line(p, axis, lines[k], z_sign), s) > 0; }) -
         1;
}

/// The cell after a small move: walked from `cell`, the same contract as locate_cell.
[[nodiscard]] inline int walk_cell(int cell, const PointMotion& p, int axis, int z_sign, int n,
                                   const double* lines, double s) {
  auto after = [&](int k) { return sign_plus(after_line(p, axis, lines[k], z_sign), s) > 0; };
  while (cell >= 0 && !after(cell)) --cell;
  while (cell + 1 < n && after(cell + 1)) ++cell;
  return cell;
}

/// The signs of one edge function at the corners 0..n - 1 of one row line: `first` at corner 0,
/// the same up to corner `count - 1`, the other sign from corner `count` on (count = n: one sign
/// all along, the edge line crosses the row line off the image or not at all).
struct CornerStep {
  int first = 1;
  int count = 0;
};

[[nodiscard]] inline int corner_sign(const EdgeNormal& n, double x, double y, double s) {
  return sign_plus(n.along(x, y), s);
}

[[nodiscard]] inline CornerStep locate_corner_step(const EdgeNormal& n, int corners,
                                                   const double* xs, double y, double s) {
  CornerStep step;
  step.first = corner_sign(n, xs[0], y, s);
  step.count = leading_count(
      corners, [&](int m) { return m == 0 || corner_sign(n, xs[m], y, s) == step.first; });
  return step;
}

/// The step after a small move, walked from `step` (one corner, at a corner event): the same
/// contract as locate_corner_step, in two or three signs instead of a bisection.
[[nodiscard]] inline CornerStep walk_corner_step(const CornerStep& step, const EdgeNormal& n,
                                                 int corners, const double* xs, double y,
                                                 double s) {
  CornerStep walked;
  walked.first = corner_sign(n, xs[0], y, s);
  // When corner 0 changed sign the step can only have entered at the left end.
  int c = walked.first == step.first ? step.count : 1;
  auto same = [&](int m) { return corner_sign(n, xs[m], y, s) == walked.first; };
  while (c > 1 && !same(c - 1)) --c;
  while (c < corners && same(c)) ++c;
  walked.count = c;
  return walked;
}

}  // namespace kinray
