// Primitive CCD against analytic times of contact, including the degenerate cases: coplanar
// motion, parallel edges, contact at a segment end, a vertex hitting an edge.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <random>

#include "kinetic/collision/exact_ccd.h"
#include "kinetic/collision/primitive_ccd.h"

namespace kinray {
namespace {

using V = Eigen::Vector3d;

PrimitiveMotion motion(std::array<V, 4> start, std::array<V, 4> end) {
  return {start, end};
}

/// The fixed triangle (0,0,0), (1,0,0), (0,1,0) and a vertex moving from a to b.
PrimitiveMotion vertex_onto_triangle(const V& a, const V& b) {
  return motion({a, V(0, 0, 0), V(1, 0, 0), V(0, 1, 0)}, {b, V(0, 0, 0), V(1, 0, 0), V(0, 1, 0)});
}

void expect_times(const std::vector<double>& got, std::vector<double> expected) {
  ASSERT_EQ(got.size(), expected.size());
  for (size_t i = 0; i < got.size(); ++i) {
    EXPECT_LE(got[i], expected[i]) << "reported late";
    EXPECT_GE(got[i], expected[i] - kContactTimeEarliness) << "reported too early";
  }
}

TEST(PrimitiveCcd, VertexFallsThroughTriangle) {
  expect_times(contact_times(ContactType::vertex_face,
                             vertex_onto_triangle(V(0.25, 0.25, 1), V(0.25, 0.25, -2))),
               {1.0 / 3.0});
}

TEST(PrimitiveCcd, VertexPassesBesideTriangle) {
  EXPECT_TRUE(contact_times(ContactType::vertex_face,
                            vertex_onto_triangle(V(0.75, 0.75, 1), V(0.75, 0.75, -1)))
                  .empty());
}

TEST(PrimitiveCcd, ContactExactlyAtTheSegmentEnds) {
  expect_times(
      contact_times(ContactType::vertex_face, vertex_onto_triangle(V(0.2, 0.2, 1), V(0.2, 0.2, 0))),
      {1.0});
  expect_times(
      contact_times(ContactType::vertex_face, vertex_onto_triangle(V(0.2, 0.2, 0), V(0.2, 0.2, 1))),
      {0.0});
}

TEST(PrimitiveCcd, VertexHitsAnEdgeAndACorner) {
  expect_times(
      contact_times(ContactType::vertex_face, vertex_onto_triangle(V(0.5, 0, 1), V(0.5, 0, -1))),
      {0.5});
  expect_times(
      contact_times(ContactType::vertex_face, vertex_onto_triangle(V(1, 0, 1), V(1, 0, -3))),
      {0.25});
  // just outside the hypotenuse by one ulp: no contact
  const double x = std::nextafter(0.5, 1.0);
  EXPECT_TRUE(
      contact_times(ContactType::vertex_face, vertex_onto_triangle(V(x, 0.5, 1), V(x, 0.5, -1)))
          .empty());
}

TEST(PrimitiveCcd, CoplanarMotionEntersAndLeaves) {
  // in the triangle's plane along y = 1/4: enters at x = 0 (t = 1/2), leaves at x = 3/4 (t = 7/8)
  expect_times(
      contact_times(ContactType::vertex_face, vertex_onto_triangle(V(-1, 0.25, 0), V(1, 0.25, 0))),
      {0.5, 0.875});
  EXPECT_TRUE(contact_times(ContactType::vertex_face, vertex_onto_triangle(V(-1, 2, 0), V(2, 2, 0)))
                  .empty());
}

/// Whether the edges (p0, p1) and (p2, p3) of the plane z = 0, each point moving linearly from
/// `start` to `end`, cross or touch at time t: the textbook orientation test in long double, a
/// computation of its own rather than the CCD's.
bool edges_meet_in_plane(const std::array<V, 4>& start, const std::array<V, 4>& end,
                         long double t) {
  std::array<std::array<long double, 2>, 4> p;
  for (int i = 0; i < 4; ++i)
    for (int c = 0; c < 2; ++c)
      p[size_t(i)][size_t(c)] =
          (long double)start[size_t(i)][c] +
          ((long double)end[size_t(i)][c] - (long double)start[size_t(i)][c]) * t;
  const auto orient = [&](int a, int b, int c) {
    return (p[b][0] - p[a][0]) * (p[c][1] - p[a][1]) - (p[b][1] - p[a][1]) * (p[c][0] - p[a][0]);
  };
  const long double d0 = orient(0, 1, 2), d1 = orient(0, 1, 3), d2 = orient(2, 3, 0),
                    d3 = orient(2, 3, 1);
  return d0 * d1 <= 0 && d2 * d3 <= 0;
}

/// The times at which edges_meet_in_plane turns true and false in [0, 1]: a scan of 10^5 steps,
/// each change bisected to the precision of long double.
std::vector<double> contact_interval_in_plane(const std::array<V, 4>& start,
                                              const std::array<V, 4>& end) {
  std::vector<double> changes;
  constexpr int kSteps = 100000;
  bool before = edges_meet_in_plane(start, end, 0);
  for (int k = 1; k <= kSteps; ++k) {
    const long double t = (long double)k / kSteps;
    const bool now = edges_meet_in_plane(start, end, t);
    if (now == before) continue;
    long double lo = (long double)(k - 1) / kSteps, hi = t;
    for (int i = 0; i < 80; ++i) {
      const long double mid = (lo + hi) / 2;
      (edges_meet_in_plane(start, end, mid) == before ? lo : hi) = mid;
    }
    changes.push_back(double(now ? hi : lo));  // the first instant of contact, the last one
    before = now;
  }
  return changes;
}

TEST(PrimitiveCcd, CoplanarContactIntervalIsReportedByItsEndsInEveryOrder) {
  // Two edges of crossing's equators (z = 0) slide over each other from t = 0.0741 to 0.0815.
  // Inside, an end of one edge passes the other edge's line four times, at times that are roots
  // of the 2-D test's polynomials for some orders of the points only: reporting them made the
  // contacts depend on which triangle pair met the edges.
  const auto h = [](const char* hex) { return std::strtod(hex, nullptr); };
  const std::array<V, 4> start = {V(h("-0x1.8fa1c63f0b98p-5"), h("-0x1.8ec6c728841f8p-6"), 0),
                                  V(h("-0x1.ae8cc0f92178p-5"), h("-0x1.2f99614d5557ap-4"), 0),
                                  V(h("0x1.8378b7de1f34p-5"), h("-0x1.921686dba6808p-6"), 0),
                                  V(h("0x1.b80226fb8177p-5"), h("-0x1.2b4c9dc037c6ep-4"), 0)};
  const std::array<V, 4> end = {V(h("0x1.2911f81a36f03p-1"), h("-0x1.3c2af37abdef8p-6"), 0),
                                V(h("0x1.28ea895f92498p-1"), h("-0x1.18457198d7256p-4"), 0),
                                V(h("-0x1.3dd215ad54a86p-1"), h("-0x1.6344db2d2f034p-6"), 0),
                                V(h("-0x1.3c376d2ac7342p-1"), h("-0x1.246cff1e6dcb6p-4"), 0)};
  const std::vector<double> expected = contact_interval_in_plane(start, end);
  ASSERT_EQ(expected.size(), 2u);  // about t = 0.0741 to 0.0815
  for (const std::array<int, 4>& order :
       {std::array{0, 1, 2, 3}, std::array{0, 1, 3, 2}, std::array{1, 0, 2, 3},
        std::array{1, 0, 3, 2}, std::array{2, 3, 0, 1}, std::array{3, 2, 1, 0}}) {
    PrimitiveMotion m;
    for (int i = 0; i < 4; ++i) {
      m.start[i] = start[order[i]];
      m.end[i] = end[order[i]];
    }
    const std::vector<double> times = contact_times(ContactType::edge_edge, m);
    ASSERT_EQ(times.size(), 2u) << order[0] << order[1] << order[2] << order[3];
    for (int k = 0; k < 2; ++k) EXPECT_NEAR(times[k], expected[k], 1e-12);
  }
}

TEST(PrimitiveCcd, RotatingTriangleSweepsAVertexInItsPlaneAtAllTimes) {
  // a degenerate triangle (all three corners equal) moving onto a vertex
  const PrimitiveMotion m = motion({V(1, 1, 1), V(0, 0, 0), V(0, 0, 0), V(0, 0, 0)},
                                   {V(1, 1, 1), V(2, 2, 2), V(2, 2, 2), V(2, 2, 2)});
  expect_times(contact_times(ContactType::vertex_face, m), {0.5});
}

TEST(PrimitiveCcd, CrossingEdges) {
  // edge a along x at z from 1 to -1, edge b along y at z = 0: they cross at t = 1/2
  const PrimitiveMotion m = motion({V(-1, 0, 1), V(1, 0, 1), V(0, -1, 0), V(0, 1, 0)},
                                   {V(-1, 0, -1), V(1, 0, -1), V(0, -1, 0), V(0, 1, 0)});
  expect_times(contact_times(ContactType::edge_edge, m), {0.5});
  // the same with edge b shifted past the end of edge a: no contact
  const PrimitiveMotion miss = motion({V(-1, 0, 1), V(1, 0, 1), V(1.5, -1, 0), V(1.5, 1, 0)},
                                      {V(-1, 0, -1), V(1, 0, -1), V(1.5, -1, 0), V(1.5, 1, 0)});
  EXPECT_TRUE(contact_times(ContactType::edge_edge, miss).empty());
}

TEST(PrimitiveCcd, ParallelEdges) {
  // parallel edges approaching in z with overlapping x ranges: touch at t = 1/2
  const PrimitiveMotion approach = motion({V(0, 0, 0), V(1, 0, 0), V(0.5, 0, 1), V(2, 0, 1)},
                                          {V(0, 0, 0), V(1, 0, 0), V(0.5, 0, -1), V(2, 0, -1)});
  expect_times(contact_times(ContactType::edge_edge, approach), {0.5});
  // collinear, sliding: b's first end reaches a's last end at x = 1, t = 4/5; they overlap after
  const PrimitiveMotion slide = motion({V(0, 0, 0), V(1, 0, 0), V(3, 0, 0), V(4, 0, 0)},
                                       {V(0, 0, 0), V(1, 0, 0), V(0.5, 0, 0), V(1.5, 0, 0)});
  const std::vector<double> times = contact_times(ContactType::edge_edge, slide);
  ASSERT_FALSE(times.empty());
  expect_times({times.front()}, {0.8});
  // parallel in one plane, never collinear
  const PrimitiveMotion apart = motion({V(0, 0, 0), V(1, 0, 0), V(3, 1, 0), V(4, 1, 0)},
                                       {V(0, 0, 0), V(1, 0, 0), V(0, 1, 0), V(1, 1, 0)});
  EXPECT_TRUE(contact_times(ContactType::edge_edge, apart).empty());
}

TEST(PrimitiveCcd, ReportedTimeIsALowerBoundWithinTheStatedEarliness) {
  // falls from z = 1 to z = -2: exact contact at t = 1/3, not a double
  const std::vector<double> t = contact_times(
      ContactType::vertex_face, vertex_onto_triangle(V(0.1, 0.1, 1), V(0.1, 0.1, -2)));
  ASSERT_EQ(t.size(), 1u);
  EXPECT_LE(mpq_class(t[0]), mpq_class(1, 3));
  EXPECT_GE(mpq_class(t[0]), mpq_class(1, 3) - mpq_class(kContactTimeEarliness));
}

/// Coordinates in {-1, -0.5, 0, 0.5, 1}: many coplanar, parallel and touching configurations.
PrimitiveMotion half_integer_motion(std::mt19937& rng) {
  std::uniform_int_distribution<int> coordinate(-2, 2);
  PrimitiveMotion m;
  for (int i = 0; i < 4; ++i)
    for (int k = 0; k < 3; ++k) {
      m.start[i][k] = coordinate(rng) * 0.5;
      m.end[i][k] = coordinate(rng) * 0.5;
    }
  return m;
}

TEST(PrimitiveCcd, FiltersNeverChangeTheExactAnswer) {
  // small integer coordinates: many coplanar, parallel and touching configurations
  std::mt19937 rng(16);
  int contacts = 0;
  for (int trial = 0; trial < 1000; ++trial) {
    const PrimitiveMotion m = half_integer_motion(rng);
    for (ContactType type : {ContactType::vertex_face, ContactType::edge_edge}) {
      const std::vector<double> filtered = contact_times(type, m);
      ASSERT_EQ(filtered, exact_contact_times(type, to_rational(m))) << "trial " << trial;
      contacts += !filtered.empty();
    }
  }
  EXPECT_GT(contacts, 100);  // the sample does exercise contacts
}

TEST(PrimitiveCcd, WindowsSplitTheContactsOfTheWholeSegment) {
  // The kinetic separation list tests a triangle pair over its overlap episodes: windows of
  // [0, 1] that share their ends must together give the whole segment's times, each at the
  // same value, and the floating-point path must agree with the exact one on every window.
  std::mt19937 rng(17);
  const double cuts[] = {0.25, 0.5, 1.0 / 3, 0.6180339887498949};
  int split_contacts = 0;
  for (int trial = 0; trial < 600; ++trial) {
    const PrimitiveMotion m = half_integer_motion(rng);
    for (ContactType type : {ContactType::vertex_face, ContactType::edge_edge}) {
      const std::vector<double> whole = contact_times(type, m);
      for (double cut : cuts) {
        const LocalWindow first = {0, cut}, second = {cut, 1}, inner = {cut / 2, cut};
        std::vector<double> joined = contact_times(type, m, nullptr, first);
        const std::vector<double> rest = contact_times(type, m, nullptr, second);
        ASSERT_EQ(joined, exact_contact_times(type, to_rational(m), first)) << "trial " << trial;
        ASSERT_EQ(rest, exact_contact_times(type, to_rational(m), second)) << "trial " << trial;
        ASSERT_EQ(contact_times(type, m, nullptr, inner),
                  exact_contact_times(type, to_rational(m), inner))
            << "trial " << trial;
        split_contacts += !joined.empty() && !rest.empty();
        joined.insert(joined.end(), rest.begin(), rest.end());
        std::ranges::sort(joined);
        joined.erase(std::unique(joined.begin(), joined.end()), joined.end());
        ASSERT_EQ(joined, whole) << "trial " << trial << " cut " << cut;
      }
    }
  }
  EXPECT_GT(split_contacts, 50);  // contacts on both sides of a cut, and at cuts
}

TEST(PrimitiveCcd, BatchGivesEachPairsFirstContactInInputOrderOnAnyThreads) {
  // both kinds mixed in one batch, in an order no thread count could keep by accident
  std::mt19937 rng(18);
  std::vector<PrimitiveQuery> queries;
  for (int trial = 0; trial < 400; ++trial)
    queries.push_back({trial % 3 == 0 ? ContactType::edge_edge : ContactType::vertex_face,
                       half_integer_motion(rng)});
  std::vector<std::optional<double>> expected;
  PrimitiveCcdCounters one_by_one;
  for (const PrimitiveQuery& q : queries) {
    const std::vector<double> times = contact_times(q.type, q.motion, &one_by_one);
    expected.push_back(times.empty() ? std::nullopt : std::optional(times.front()));
  }
  ASSERT_GT(std::ranges::count_if(expected, [](auto t) { return t.has_value(); }), 40);
  for (int threads : {1, 2, 3, 0}) {
    PrimitiveCcdCounters batch;
    EXPECT_EQ(first_contact_times(queries, &batch, {.threads = threads}), expected)
        << threads << " threads";
    EXPECT_EQ(batch.tests, queries.size());
    EXPECT_EQ(batch.contacts, one_by_one.contacts);
    EXPECT_EQ(batch.exact_decisions, one_by_one.exact_decisions);
  }
  EXPECT_TRUE(first_contact_times({}, nullptr, {.threads = 2}).empty());
}

TEST(PrimitiveCcd, ContactPointOfCrossingEdges) {
  const PrimitiveMotion m = motion({V(-1, 0, 1), V(1, 0, 1), V(0, -1, 0), V(0, 1, 0)},
                                   {V(-1, 0, -1), V(1, 0, -1), V(0, -1, 0), V(0, 1, 0)});
  EXPECT_NEAR((contact_point(ContactType::edge_edge, m, 0.5) - V(0, 0, 0)).norm(), 0, 1e-12);
}

}  // namespace
}  // namespace kinray
