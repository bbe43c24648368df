// The interval decision of primitive CCD against the rational one: where it decides, it gives
// the rational answer to the bit (the same times, on the grid of kContactTimeEarliness), for
// every order of the pair's points; where it cannot, it says so.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "kinetic/collision/exact_ccd.h"
#include "kinetic/collision/interval_ccd.h"
#include "kinetic/collision/primitive_ccd.h"

namespace kinray {
namespace {

using V = Eigen::Vector3d;

/// A pair near contact with coordinates that are not small dyadics: a point-like first
/// primitive moving through the second one's region, everything jittered.
PrimitiveMotion random_near_contact(std::mt19937& rng) {
  std::uniform_real_distribution<double> unit(-1, 1);
  const auto random_vector = [&](double scale) -> V {
    return V(unit(rng), unit(rng), unit(rng)) * scale;
  };
  PrimitiveMotion m;
  for (int i = 0; i < 4; ++i) {
    m.start[i] = random_vector(1);
    m.end[i] = m.start[i] + random_vector(0.3);
  }
  // pull the first point(s) through the middle of the others
  const V centre = (m.start[2] + m.start[3]) / 2 + random_vector(0.2);
  const V through = random_vector(1);
  m.start[0] = centre + through;
  m.end[0] = centre - through;
  return m;
}

void rotate_face(PrimitiveMotion& m) {
  std::rotate(m.start.begin() + 1, m.start.begin() + 2, m.start.end());
  std::rotate(m.end.begin() + 1, m.end.begin() + 2, m.end.end());
}

void swap_points(PrimitiveMotion& m, int a, int b) {
  std::swap(m.start[a], m.start[b]);
  std::swap(m.end[a], m.end[b]);
}

TEST(IntervalCcd, DecidesMostPairsNearContactAndAgreesWithTheRationalDecision) {
  std::mt19937 rng(16);
  int decided = 0, contacts = 0;
  constexpr int kTrials = 400;
  for (int trial = 0; trial < kTrials; ++trial) {
    const PrimitiveMotion m = random_near_contact(rng);
    for (ContactType type : {ContactType::vertex_face, ContactType::edge_edge}) {
      IntervalCcdCounters counters;
      const std::optional<std::vector<double>> times = interval_contact_times(type, m, counters);
      if (!times) continue;
      ++decided;
      contacts += !times->empty();
      ASSERT_EQ(*times, exact_contact_times(type, to_rational(m))) << "trial " << trial;
      for (double t : *times) EXPECT_EQ(t, std::floor(t / kContactTimeEarliness) * kContactTimeEarliness);
    }
  }
  EXPECT_GT(decided, 2 * kTrials * 9 / 10);  // the filter is what makes CCD fast
  EXPECT_GT(contacts, kTrials / 4);          // and it does decide contacts, not only misses
}

TEST(IntervalCcd, AgreesWithTheRationalDecisionFarFromTheOrigin) {
  // Far from the origin the differences of coordinates lose their low bits: the grid points
  // next to a root are signed with the most cancellation, where a too small error bound would
  // give a wrong time.
  std::mt19937 rng(23);
  std::uniform_real_distribution<double> offset(-1e6, 1e6);
  int contacts = 0;
  for (int trial = 0; trial < 300; ++trial) {
    PrimitiveMotion m = random_near_contact(rng);
    const V shift(offset(rng), offset(rng), offset(rng));
    for (int i = 0; i < 4; ++i) {
      m.start[i] += shift;
      m.end[i] += shift;
    }
    for (ContactType type : {ContactType::vertex_face, ContactType::edge_edge}) {
      IntervalCcdCounters counters;
      const std::optional<std::vector<double>> times = interval_contact_times(type, m, counters);
      if (!times) continue;
      contacts += !times->empty();
      ASSERT_EQ(*times, exact_contact_times(type, to_rational(m))) << "trial " << trial;
    }
  }
  EXPECT_GT(contacts, 50);
}

TEST(IntervalCcd, ExtendedCubicSignIsRightOrUndecidedNextToARoot) {
  // A vertex creeping through a face (1e-4 of the face's size over the segment): the cubic's
  // slope is tiny against its terms, so next to its root rounding decides the computed sign
  // unless the error bound holds it back. The grid points are the doubles next to the root.
  std::mt19937 rng(41);
  std::uniform_real_distribution<double> unit(-1, 1), inside(0.1, 0.3), when(0.05, 0.95);
  int decided = 0, undecided = 0;
  for (int trial = 0; trial < 200; ++trial) {
    PrimitiveMotion m;
    for (int i = 1; i < 4; ++i) {
      m.start[i] = V(unit(rng), unit(rng), unit(rng)) * 1e3 + V(1e5, -2e4, 3e3);
      m.end[i] = m.start[i] + V(unit(rng), unit(rng), unit(rng)) * 1e-2;
    }
    const V normal = (m.start[2] - m.start[1]).cross(m.start[3] - m.start[1]).normalized();
    const V point = m.start[1] + inside(rng) * (m.start[2] - m.start[1]) +
                    inside(rng) * (m.start[3] - m.start[1]);
    const double t = when(rng);
    m.start[0] = point + 0.1 * t * normal;
    m.end[0] = point - 0.1 * (1 - t) * normal;
    const RationalPolynomial cubic = coplanarity_polynomial(to_rational(m));
    const auto exact_sign = [&](double g) { return sign(cubic(mpq_class(g))); };
    // the double where the exact sign changes, by bisection over doubles
    double lo = 0, hi = 1;
    const int sign_lo = exact_sign(lo);
    if (sign_lo == 0 || exact_sign(hi) != -sign_lo) continue;
    while (std::nextafter(lo, 2.0) < hi) {
      const double mid = 0.5 * (lo + hi);
      (exact_sign(mid) == sign_lo ? lo : hi) = mid;
    }
    double g = lo;
    for (int i = 0; i < 3; ++i) g = std::nextafter(g, -1.0);
    for (int i = 0; i < 8; ++i, g = std::nextafter(g, 2.0)) {
      const int computed = detail::extended_cubic_sign(m, g);
      if (computed == 0) {
        ++undecided;
        continue;
      }
      ++decided;
      ASSERT_EQ(computed, exact_sign(g)) << "trial " << trial << ", g = " << g;
    }
  }
  EXPECT_GT(decided, 0);
  EXPECT_GT(undecided, 0);  // the bound does hold some back: these are the hard cases
}

TEST(IntervalCcd, SameTimesForEveryOrderOfThePairsPoints) {
  // One primitive pair meets several triangle pairs with its points in other orders; the
  // contact lists deduplicate it only if every order reports the same times.
  std::mt19937 rng(7);
  for (int trial = 0; trial < 200; ++trial) {
    const PrimitiveMotion m = random_near_contact(rng);
    const std::vector<double> vf = contact_times(ContactType::vertex_face, m);
    PrimitiveMotion rotated = m;
    rotate_face(rotated);
    EXPECT_EQ(contact_times(ContactType::vertex_face, rotated), vf) << "trial " << trial;
    swap_points(rotated, 1, 2);
    EXPECT_EQ(contact_times(ContactType::vertex_face, rotated), vf) << "trial " << trial;

    const std::vector<double> ee = contact_times(ContactType::edge_edge, m);
    PrimitiveMotion other = m;
    swap_points(other, 0, 2);
    swap_points(other, 1, 3);
    EXPECT_EQ(contact_times(ContactType::edge_edge, other), ee) << "trial " << trial;
    swap_points(other, 0, 1);
    EXPECT_EQ(contact_times(ContactType::edge_edge, other), ee) << "trial " << trial;
  }
}

TEST(IntervalCcd, LeavesDegenerateMotionToTheRationalDecision) {
  IntervalCcdCounters counters;
  // coplanar motion: the cubic vanishes identically, no sub-interval is certain
  const PrimitiveMotion sliding = {{V(0.2, 0.2, 0), V(0, 0, 0), V(1, 0, 0), V(0, 1, 0)},
                                   {V(2, 2, 0), V(0, 0, 0), V(1, 0, 0), V(0, 1, 0)}};
  EXPECT_FALSE(interval_contact_times(ContactType::vertex_face, sliding, counters));
  // the vertex hits the triangle's edge: a barycentric sign is zero at the contact (the edge
  // along (1, 1, 1) - (0, 0, 0), so that no axis plane holds the vertex and the edge)
  const PrimitiveMotion on_edge = {
      {V(0.5, 0.5, 0.5) + V(0.1, -0.3, 0.2), V(0, 0, 0), V(1, 1, 1), V(1, 0, 0)},
      {V(0.5, 0.5, 0.5) - V(0.1, -0.3, 0.2), V(0, 0, 0), V(1, 1, 1), V(1, 0, 0)}};
  EXPECT_FALSE(interval_contact_times(ContactType::vertex_face, on_edge, counters));
  // and a clear hit is decided, at the rational decision's time
  const PrimitiveMotion hit = {{V(0.25, 0.25, 1), V(0, 0, 0), V(1, 0, 0), V(0, 1, 0)},
                               {V(0.25, 0.25, -2), V(0, 0, 0), V(1, 0, 0), V(0, 1, 0)}};
  const std::optional<std::vector<double>> times =
      interval_contact_times(ContactType::vertex_face, hit, counters);
  ASSERT_TRUE(times);
  EXPECT_EQ(*times, exact_contact_times(ContactType::vertex_face, to_rational(hit)));
  // so is a contact exactly at the segment end, where the cubic's exact sign is zero and the
  // vertex certainly inside the triangle
  const PrimitiveMotion landing = {{V(0.2, 0.2, 1), V(0, 0, 0), V(1, 0, 0), V(0, 1, 0)},
                                   {V(0.2, 0.2, 0), V(0, 0, 0), V(1, 0, 0), V(0, 1, 0)}};
  const std::optional<std::vector<double>> landed =
      interval_contact_times(ContactType::vertex_face, landing, counters);
  ASSERT_TRUE(landed);
  EXPECT_EQ(*landed, std::vector<double>{1.0});
  EXPECT_EQ(counters.contacts, 2u);
}

/// Three points on the plane `axis` = c for the whole segment, jittered: P crosses the line of
/// the segment (S0, S1) inside it (or, with `miss`, beyond S1), and Q stays above the plane.
/// Points in the order P, S0, S1, Q.
PrimitiveMotion point_crossing_segment_in_axis_plane(std::mt19937& rng, int axis, bool miss) {
  std::uniform_real_distribution<double> unit(-1, 1), along(0.2, 0.8), when(0.1, 0.9);
  const double c = 0.3 + 0.1 * unit(rng);
  const auto planar = [&](double x, double y) {
    V p;
    p[axis] = c;
    p[(axis + 1) % 3] = x;
    p[(axis + 2) % 3] = y;
    return p;
  };
  PrimitiveMotion m;
  m.start[1] = planar(unit(rng), unit(rng));
  m.start[2] = m.start[1] + planar(1 + 0.2 * unit(rng), 0.2 * unit(rng)) - planar(0, 0);
  for (int i = 1; i < 3; ++i)
    m.end[i] = m.start[i] + planar(0.05 * unit(rng), 0.05 * unit(rng)) - planar(0, 0);
  // P crosses at local time t through the point s of the way from S0 to S1 (at t), moving
  // across the segment's direction
  const double t = when(rng), s = miss ? 1.3 : along(rng);
  const V s0 = m.start[1] + t * (m.end[1] - m.start[1]),
          s1 = m.start[2] + t * (m.end[2] - m.start[2]);
  const V hit = s0 + s * (s1 - s0);
  const V across = planar(0.1 * unit(rng), 0.5 + 0.2 * unit(rng)) - planar(0, 0);
  m.start[0] = hit - t * across;
  m.end[0] = hit + (1 - t) * across;
  m.start[3] = planar(unit(rng), unit(rng));
  m.start[3][axis] = c + 0.5 + 0.1 * unit(rng);
  m.end[3] = m.start[3] + 0.1 * V(unit(rng), unit(rng), unit(rng));
  return m;
}

TEST(IntervalCcd, DecidesAPointOnASegmentInAnAxisPlane) {
  // A vertex of a flat region crossing an edge of it, seen as vertex-face (the face's third
  // corner off the plane) and as edge-edge (the vertex's edge leaving the plane): the general
  // test's condition through the three planar points vanishes at the contact, the axis plane's
  // test decides it, at the rational decision's time, in every order of the points.
  std::mt19937 rng(15);
  int decided = 0, contacts = 0, pairs = 0;
  for (int trial = 0; trial < 150; ++trial) {
    const PrimitiveMotion m = point_crossing_segment_in_axis_plane(rng, trial % 3, trial % 5 == 0);
    // vertex-face: the vertex P, the face (S0, S1, Q) in each rotation
    PrimitiveMotion vf = m;
    // edge-edge: (P, Q) against (S0, S1), and the edges the other way round
    PrimitiveMotion ee = m;
    swap_points(ee, 1, 3);  // P, Q, S1, S0
    PrimitiveMotion ee_swapped = ee;
    swap_points(ee_swapped, 0, 2);
    swap_points(ee_swapped, 1, 3);  // S1, S0, P, Q
    std::vector<std::pair<ContactType, PrimitiveMotion>> cases;
    for (int r = 0; r < 3; ++r, rotate_face(vf)) cases.emplace_back(ContactType::vertex_face, vf);
    cases.emplace_back(ContactType::edge_edge, ee);
    cases.emplace_back(ContactType::edge_edge, ee_swapped);
    for (const auto& [type, motion] : cases) {
      ++pairs;
      IntervalCcdCounters counters;
      const std::optional<std::vector<double>> times =
          interval_contact_times(type, motion, counters);
      if (!times) continue;
      ++decided;
      contacts += !times->empty();
      ASSERT_EQ(*times, exact_contact_times(type, to_rational(motion))) << "trial " << trial;
    }
  }
  EXPECT_GT(decided, pairs * 9 / 10);
  EXPECT_GT(contacts, pairs / 2);
}

TEST(IntervalCcd, DecidesEdgesSlidingInAnAxisPlane) {
  // Two edges of a flat region moving in its plane (coplanar motion: the cubic vanishes
  // identically) touch over intervals of time, reported by their first and last times and by
  // the window's ends 0 and 1: the same times as the rational decision, on whole segments and
  // on windows, in every order of the points.
  std::mt19937 rng(151);
  std::uniform_real_distribution<double> unit(-1, 1), cut(0, 1);
  int decided = 0, with_contact = 0, pairs = 0;
  for (int trial = 0; trial < 200; ++trial) {
    const int axis = trial % 3;
    const double c = 0.25 + 0.1 * unit(rng);
    PrimitiveMotion m;
    for (int i = 0; i < 4; ++i) {
      m.start[i] = V(unit(rng), unit(rng), unit(rng));
      m.end[i] = m.start[i] + V(unit(rng), unit(rng), unit(rng));
      m.start[i][axis] = m.end[i][axis] = c;
    }
    double lo = cut(rng), hi = cut(rng);
    if (hi < lo) std::swap(lo, hi);
    for (const LocalWindow window : {LocalWindow{}, LocalWindow{lo, hi}, LocalWindow{0, hi}}) {
      PrimitiveMotion other = m;
      swap_points(other, 0, 3);
      swap_points(other, 1, 2);  // b1, b0, a1, a0
      for (const PrimitiveMotion& motion : {m, other}) {
        ++pairs;
        const std::vector<double> exact =
            exact_contact_times(ContactType::edge_edge, to_rational(motion), window);
        with_contact += !exact.empty();
        IntervalCcdCounters counters;
        const std::optional<std::vector<double>> times =
            interval_contact_times(ContactType::edge_edge, motion, counters, window);
        if (!times) continue;
        ++decided;
        ASSERT_EQ(*times, exact) << "trial " << trial << ", window " << window.lo << " "
                                 << window.hi;
      }
    }
  }
  EXPECT_GT(with_contact, pairs / 5);
  EXPECT_GT(decided, pairs * 9 / 10);
}

/// An edge-edge pair decided both ways: counts whether it has a contact and whether floating
/// point decided it, and where it did, expects the rational decision's times.
void decide_edges(const PrimitiveMotion& m, int trial, int& with_contact, int& decided) {
  const std::vector<double> exact = exact_contact_times(ContactType::edge_edge, to_rational(m));
  with_contact += !exact.empty();
  IntervalCcdCounters counters;
  const std::optional<std::vector<double>> times =
      interval_contact_times(ContactType::edge_edge, m, counters);
  if (!times) return;
  ++decided;
  EXPECT_EQ(*times, exact) << "trial " << trial;
}

TEST(IntervalCcd, DecidesARootExactlyAtADouble) {
  // A vertex reaching a tilted triangle's plane exactly at local time 0, 1/2 or 1 (a key pose in
  // contact, or a piece boundary of the bisection), inside the triangle or beside it: the cubic's
  // exact sign there is zero, and the 2-D test at that time decides, as the rational decision
  // does.
  std::mt19937 rng(29);
  // dyadic coordinates, so that every position below is exact and the root exactly at t
  std::uniform_int_distribution<int> pick(0, 2), sixty_fourths(-20, 60), sixteenths(-4, 4);
  int decided = 0, with_contact = 0;
  constexpr int kTrials = 300;
  for (int trial = 0; trial < kTrials; ++trial) {
    const V f0(0, 0, 0), f1(1, 0, 0.5), f2(0, 1, 0.25);
    // a point of the plane z = x / 2 + y / 4, in or out of the triangle
    const double x = sixty_fourths(rng) / 64.0, y = sixty_fourths(rng) / 64.0;
    const V on(x, y, x / 2 + y / 4);
    const double when[3] = {0, 0.5, 1};
    const double t = when[pick(rng)];
    // linear motion through `on` at t: at t = 0 start there, at 1 end there, at 1/2 symmetric
    const V d = V(sixteenths(rng) / 16.0, sixteenths(rng) / 16.0, 1);
    const PrimitiveMotion m = {{on - t * d, f0, f1, f2}, {on + (1 - t) * d, f0, f1, f2}};
    const std::vector<double> exact = exact_contact_times(ContactType::vertex_face, to_rational(m));
    with_contact += !exact.empty();
    IntervalCcdCounters counters;
    const std::optional<std::vector<double>> times =
        interval_contact_times(ContactType::vertex_face, m, counters);
    if (!times) continue;
    ++decided;
    EXPECT_EQ(*times, exact) << "trial " << trial;
  }
  EXPECT_GT(with_contact, kTrials / 5);
  EXPECT_LT(with_contact, kTrials * 4 / 5);
  EXPECT_GT(decided, kTrials * 9 / 10);
}

TEST(IntervalCcd, DecidesARootWithinRoundingOfTheSegmentsEnd) {
  // A key pose with two edges in contact, or nearly (a cloth folded onto itself at a key): the
  // cubic's root lies within rounding of local time 1, before or after it, and no bisection
  // separates it from the end. The cubic's exact sign at the end decides it, with the rational
  // decision's answer.
  std::mt19937 rng(47);
  std::uniform_real_distribution<double> unit(-1, 1), along(0.2, 0.8), tiny(1e-17, 1e-15);
  int decided = 0, with_contact = 0;
  constexpr int kTrials = 200;
  for (int trial = 0; trial < kTrials; ++trial) {
    const V a0(unit(rng), unit(rng), unit(rng)), a1(unit(rng), unit(rng), unit(rng));
    const V d = V(unit(rng), unit(rng), unit(rng)).normalized();
    const V normal = (a1 - a0).cross(d).normalized();
    // edge b crosses edge a at x at the key, offset along the normal by a few ulps, either way
    const V x = a0 + along(rng) * (a1 - a0) + (trial % 2 == 0 ? 1 : -1) * tiny(rng) * normal;
    PrimitiveMotion m;
    m.end = {a0, a1, x - (0.3 + along(rng)) * d, x + (0.3 + along(rng)) * d};
    const V towards = 0.5 * normal + 0.2 * V(unit(rng), unit(rng), unit(rng));
    for (int i = 0; i < 4; ++i)
      m.start[size_t(i)] = m.end[size_t(i)] + (i < 2 ? 0.05 : 1.0) * (i < 2 ? d : towards);
    decide_edges(m, trial, with_contact, decided);
  }
  EXPECT_GT(with_contact, kTrials / 4);
  EXPECT_LT(with_contact, kTrials);
  EXPECT_GT(decided, kTrials * 9 / 10);
}

TEST(IntervalCcd, DecidesAContactOrAMissJustBesideAnEdgeOrAnEnd) {
  // A vertex through its triangle, or an edge through another, at mid-segment, a distance of
  // 1e-12 to 1e-8 inside or outside the triangle's edge (the other edge's end): the 2-D test's
  // polynomials are that small at the root and change faster over any piece the bisection
  // reaches (the wedges of Erleben's tests). The root's grid cell decides them, as the rational
  // decision does.
  std::mt19937 rng(91);
  std::uniform_real_distribution<double> unit(-1, 1), exponent(-12, -8);
  for (const ContactType type : {ContactType::vertex_face, ContactType::edge_edge}) {
    int decided = 0, with_contact = 0;
    constexpr int kTrials = 200;
    for (int trial = 0; trial < kTrials; ++trial) {
      const V p0(unit(rng), unit(rng), unit(rng)), p1(unit(rng), unit(rng), unit(rng));
      const V q(unit(rng), unit(rng), unit(rng));
      const V normal = (p1 - p0).cross(q - p0).normalized();
      // the crossing point beside the edge p0 p1 (the triangle p0 p1 q's, or edge a's end p1),
      // in the plane, on the side of q or away from it
      const V inward =
          normal.cross(p1 - p0).normalized() * ((q - p0).dot(normal.cross(p1 - p0)) > 0 ? 1 : -1);
      const double offset = (trial % 2 == 0 ? 1 : -1) * std::pow(10.0, exponent(rng));
      PrimitiveMotion m;
      const V through = 0.5 * normal + 0.1 * V(unit(rng), unit(rng), unit(rng));
      if (type == ContactType::vertex_face) {
        const V x = p0 + 0.4 * (p1 - p0) + offset * inward;
        m.start = {x + through, p0, p1, q};
        m.end = {x - through, p0, p1, q};
      } else {
        // edge a from p1 back along q - p1 (so p1 is its end), edge b through p1 + offset along
        // a's direction: inside a or beyond its end
        const V dir = (q - p1).normalized(), cross_dir = normal.cross(dir).normalized();
        const V x = p1 + offset * dir;
        m.start = {p1 + through, q + through, x - 0.5 * cross_dir, x + 0.5 * cross_dir};
        m.end = {p1 - through, q - through, x - 0.5 * cross_dir, x + 0.5 * cross_dir};
      }
      const std::vector<double> exact = exact_contact_times(type, to_rational(m));
      with_contact += !exact.empty();
      IntervalCcdCounters counters;
      const std::optional<std::vector<double>> times = interval_contact_times(type, m, counters);
      if (!times) continue;
      ++decided;
      EXPECT_EQ(*times, exact) << contact_type_name(type) << " trial " << trial;
    }
    EXPECT_GT(with_contact, kTrials / 3) << contact_type_name(type);
    EXPECT_LT(with_contact, kTrials * 2 / 3) << contact_type_name(type);
    EXPECT_GT(decided, kTrials * 9 / 10) << contact_type_name(type);
  }
}

TEST(IntervalCcd, DecidesEdgesSlidingInAnAxisPlanePastEachOthersEnds) {
  // An edge sliding in an axis plane whose end passes close by the end of another edge there:
  // both edges' orientations change sign within a short time of each other (the distance over
  // the speed), and the bisection must go deep to order them.
  std::mt19937 rng(83);
  std::uniform_real_distribution<double> unit(-1, 1);
  int decided = 0, with_contact = 0;
  constexpr int kTrials = 100;
  for (int trial = 0; trial < kTrials; ++trial) {
    const double c = 0.5 + 0.1 * unit(rng), gap = std::ldexp(1 + unit(rng), -14 - trial % 6);
    const V a0(unit(rng), unit(rng), c), a1(unit(rng), unit(rng), c);
    const V side = V(a0.y() - a1.y(), a1.x() - a0.x(), 0).normalized();
    // b's first end passes a1 at the given distance, on one side or the other, at mid-segment
    const V pass = a1 + (trial % 2 == 0 ? gap : -gap) * side;
    const V velocity(unit(rng), unit(rng), 0), b_edge(unit(rng), unit(rng), 0);
    PrimitiveMotion m;
    m.start = {a0, a1, pass - 0.5 * velocity, pass - 0.5 * velocity + b_edge};
    m.end = {a0, a1, pass + 0.5 * velocity, pass + 0.5 * velocity + b_edge};
    for (int i = 0; i < 4; ++i) m.start[size_t(i)].z() = m.end[size_t(i)].z() = c;
    decide_edges(m, trial, with_contact, decided);
  }
  EXPECT_GT(with_contact, kTrials / 4);
  EXPECT_GT(decided, kTrials * 9 / 10);
}

}  // namespace
}  // namespace kinray
