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
  // contact exactly at the segment end: the cubic is zero there
  const PrimitiveMotion landing = {{V(0.2, 0.2, 1), V(0, 0, 0), V(1, 0, 0), V(0, 1, 0)},
                                   {V(0.2, 0.2, 0), V(0, 0, 0), V(1, 0, 0), V(0, 1, 0)}};
  EXPECT_FALSE(interval_contact_times(ContactType::vertex_face, landing, counters));
  // the vertex hits the triangle's edge: a barycentric sign is zero at the contact
  const PrimitiveMotion on_edge = {{V(0.5, 0, 1), V(0, 0, 0), V(1, 0, 0), V(0, 1, 0)},
                                   {V(0.5, 0, -1), V(0, 0, 0), V(1, 0, 0), V(0, 1, 0)}};
  EXPECT_FALSE(interval_contact_times(ContactType::vertex_face, on_edge, counters));
  // and a clear hit is decided, at the rational decision's time
  const PrimitiveMotion hit = {{V(0.25, 0.25, 1), V(0, 0, 0), V(1, 0, 0), V(0, 1, 0)},
                               {V(0.25, 0.25, -2), V(0, 0, 0), V(1, 0, 0), V(0, 1, 0)}};
  const std::optional<std::vector<double>> times =
      interval_contact_times(ContactType::vertex_face, hit, counters);
  ASSERT_TRUE(times);
  EXPECT_EQ(*times, exact_contact_times(ContactType::vertex_face, to_rational(hit)));
  EXPECT_EQ(counters.contacts, 1u);
}

}  // namespace
}  // namespace kinray
