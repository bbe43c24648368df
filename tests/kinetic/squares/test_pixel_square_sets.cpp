// The per-square sets against brute force: each pixel's set must be exactly the triangles whose
// region overlaps its closed square (square_overlap, ties aside) at any time between events, on
// a small synthetic scene built to reach every case (straddling the eye plane, behind the
// camera, crossing the eye plane, slivers through a square that cover no corner and hold no
// vertex), on random triangles across the eye plane, with exact answers where geometry gives
// them, no event at all for a static scene, event counts independent of the frames, one event
// per corner for a shared edge, and a change log that replays the sets.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "kinetic/squares/pixel_square_sets.h"
#include "tests/kinetic/squares/square_test_scenes.h"

namespace kinray {
namespace {

using test::at_depth;
using test::expect_matches_brute_force;
using test::image_triangle;
using test::moving_triangle;
using test::random_scene;
using test::random_times;
using test::synthetic_scene;
using test::TestScene;
using Vec = Eigen::Vector3d;

TEST(PixelSquareSets, SyntheticSceneMatchesBruteForceAtRandomTimes) {
  const TestScene scene = synthetic_scene();
  PixelSquareSets sets(scene.input(), -0.25);
  size_t ties = 0;
  EXPECT_TRUE(sets.audit(&ties).empty());
  ties += expect_matches_brute_force(sets, random_times(-0.25, 2.3, 400, 7));
  const SquareStats stats = sets.stats();
  // The scene reaches every kind of event, and both kinds of record.
  EXPECT_GT(stats.events.corner, 0u);
  EXPECT_GT(stats.events.side, 0u);
  EXPECT_GT(stats.events.row, 0u);
  EXPECT_GT(stats.events.rebuild, 0u);
  EXPECT_EQ(stats.events.flightplan, 3u * scene.meshes.size());  // keys 0, 1 and 2
  EXPECT_GT(stats.triangles_straddling, 0u);
  EXPECT_GT(stats.triangles_front, 0u);
  // Ties (an edge or a vertex within 1e-9 of a square's side) are accidents of the geometry,
  // and the jittered scene has next to none: nearly every pair is a clear answer checked.
  EXPECT_LT(ties, 10u);
}

TEST(PixelSquareSets, SyntheticSceneAtItsEventsAndKeys) {
  // The times just after keys and at them, where segments switch and records are rebuilt.
  const TestScene scene = synthetic_scene();
  PixelSquareSets sets(scene.input(), 0.0, {.audit = true});
  for (double t : {1e-9, 0.5, 1.0, 1.0 + 1e-9, 1.7, 2.0, 2.0 + 1e-6, 3.0}) {
    EXPECT_NO_THROW(sets.advance_to(t)) << "t = " << t;
  }
}

TEST(PixelSquareSets, AppearingAndDisappearingMeshes) {
  TestScene scene = synthetic_scene();
  scene.meshes[0].appear = 0.3;
  scene.meshes[1].disappear = 1.4;
  scene.meshes[2].appear = 0.8;
  scene.meshes[2].disappear = 1.9;
  PixelSquareSets sets(scene.input(), 0.0);
  expect_matches_brute_force(sets, random_times(0.0, 2.2, 120, 11));
  EXPECT_EQ(sets.stats().events.insert, 2u);
  EXPECT_EQ(sets.stats().events.remove, 2u);
}

TEST(PixelSquareSets, RandomTrianglesAcrossTheEyePlaneMatchBruteForce) {
  // Every mode (before, across, behind the eye) and every change between them, on separate
  // triangles and on a mesh whose vertices are shared, and on images down to one pixel.
  struct Case {
    unsigned seed;
    int width, height;
    bool welded;
  };
  for (const Case& c : {Case{1, 20, 14, false}, Case{2, 20, 14, false}, Case{3, 20, 14, true},
                        Case{4, 20, 14, true}, Case{5, 1, 1, false}, Case{6, 3, 2, true}}) {
    const TestScene scene = random_scene(c.seed, c.width, c.height, c.welded);  // outlives sets
    PixelSquareSets sets(scene.input(), 0.0);
    const size_t ties = expect_matches_brute_force(sets, random_times(0.0, 2.1, 150, c.seed));
    EXPECT_LT(ties, 10u) << "seed " << c.seed;
    EXPECT_GT(sets.stats().events.rebuild, 0u) << "seed " << c.seed;
  }
}

TEST(PixelSquareSets, AnEdgeSharedByTwoTrianglesCrossesACornerOnce) {
  // A quad of two triangles sliding across the image, once welded (the diagonal one edge, its
  // vertices followed once) and once as two separate triangles: the same sets, and the welded
  // quad counts each corner its diagonal crosses once instead of twice.
  const std::vector<double> times = {0.0, 1.0};
  const std::array<std::array<double, 2>, 4> corners = {
      {{-0.9, -0.5}, {0.1, -0.45}, {0.15, 0.55}, {-0.85, 0.5}}};
  auto at = [&](size_t c, int key) {
    return at_depth(corners[c][0] + 0.8 * key, corners[c][1] + 0.1 * key, 2.0);
  };
  TestScene welded, separate;
  welded.width = separate.width = 16;
  welded.height = separate.height = 12;
  test::OwnedMesh quad;
  quad.times = times;
  quad.vertex_count = 4;
  for (int key = 0; key < 2; ++key)
    for (size_t c = 0; c < 4; ++c) quad.positions.push_back(at(c, key));
  quad.triangles = {{0, 1, 2}, {0, 2, 3}};
  welded.meshes.push_back(quad);
  for (const auto& tri : quad.triangles) {
    std::vector<std::array<Vec, 3>> keys;
    for (int key = 0; key < 2; ++key)
      keys.push_back({at(tri[0], key), at(tri[1], key), at(tri[2], key)});
    separate.meshes.push_back(moving_triangle(times, keys));
  }
  PixelSquareSets a(welded.input(), 0.0), b(separate.input(), 0.0);
  expect_matches_brute_force(a, random_times(0.0, 1.0, 20, 23));
  expect_matches_brute_force(b, random_times(0.0, 1.0, 20, 23));
  for (int j = 0; j < 12; ++j)
    for (int i = 0; i < 16; ++i) EXPECT_EQ(a.triangles(i, j).size(), b.triangles(i, j).size());
  EXPECT_EQ(a.stats().edges_followed, 5u);
  EXPECT_EQ(b.stats().edges_followed, 6u);
  EXPECT_GT(a.stats().events.corner, 0u);
  EXPECT_LT(a.stats().events.corner, b.stats().events.corner);
  EXPECT_LT(a.stats().events.side, b.stats().events.side);
}

TEST(PixelSquareSets, EventsDoNotDependOnTheFramesReadOut) {
  const TestScene scene = synthetic_scene();
  PixelSquareSets once(scene.input(), -0.25), often(scene.input(), -0.25);
  once.advance_to(2.3);
  for (int f = 1; f <= 500; ++f) often.advance_to(-0.25 + 2.55 * f / 500);
  const SquareStats a = once.stats(), b = often.stats();
  EXPECT_EQ(a.events.corner, b.events.corner);
  EXPECT_EQ(a.events.side, b.events.side);
  EXPECT_EQ(a.events.row, b.events.row);
  EXPECT_EQ(a.events.rebuild, b.events.rebuild);
  EXPECT_EQ(a.events.flightplan, b.events.flightplan);
  for (int j = 0; j < 12; ++j)
    for (int i = 0; i < 16; ++i) {
      auto x = once.triangles(i, j), y = often.triangles(i, j);
      std::vector<SquareTriangle> u(x.begin(), x.end()), v(y.begin(), y.end());
      auto less = [](const SquareTriangle& p, const SquareTriangle& q) {
        return p.mesh != q.mesh ? p.mesh < q.mesh : p.triangle < q.triangle;
      };
      std::sort(u.begin(), u.end(), less);
      std::sort(v.begin(), v.end(), less);
      EXPECT_EQ(u, v) << "pixel (" << i << ", " << j << ")";
    }
}

TEST(PixelSquareSets, ChangeLogReplaysTheSets) {
  // The sets at the start plus the logged changes, in order, are the sets at the end; every
  // change lies in the interval of the advance that made it.
  const TestScene scene = synthetic_scene();
  PixelSquareSets sets(scene.input(), -0.25);
  std::vector<std::vector<SquareTriangle>> replay(16 * 12);
  for (int j = 0; j < 12; ++j)
    for (int i = 0; i < 16; ++i) {
      const auto set = sets.triangles(i, j);
      replay[size_t(j * 16 + i)].assign(set.begin(), set.end());
    }
  sets.log_changes(true);
  double before = sets.now();
  for (double t : random_times(-0.25, 2.3, 30, 17)) {
    sets.advance_to(t);
    for (const SquareChange& c : sets.changes()) {
      EXPECT_GT(c.time, before);
      EXPECT_LE(c.time, t);
      std::vector<SquareTriangle>& set = replay[c.pixel];
      const auto it = std::find(set.begin(), set.end(), c.triangle);
      if (c.entered) {
        EXPECT_EQ(it, set.end());
        set.push_back(c.triangle);
      } else {
        ASSERT_NE(it, set.end());
        set.erase(it);
      }
    }
    sets.clear_changes();
    before = t;
  }
  auto less = [](const SquareTriangle& p, const SquareTriangle& q) {
    return p.mesh != q.mesh ? p.mesh < q.mesh : p.triangle < q.triangle;
  };
  for (int j = 0; j < 12; ++j)
    for (int i = 0; i < 16; ++i) {
      const auto set = sets.triangles(i, j);
      std::vector<SquareTriangle> now(set.begin(), set.end()),
          replayed = replay[size_t(j * 16 + i)];
      std::sort(now.begin(), now.end(), less);
      std::sort(replayed.begin(), replayed.end(), less);
      EXPECT_EQ(now, replayed) << "pixel (" << i << ", " << j << ")";
    }
  EXPECT_GT(sets.stats().square_changes, 0u);
}

/// The columns of row j holding mesh m's triangle 0.
std::vector<int> columns_holding(const PixelSquareSets& sets, uint32_t m, int j) {
  std::vector<int> columns;
  for (int i = 0; i < sets.lattice().width(); ++i) {
    const auto set = sets.triangles(i, j);
    if (std::find(set.begin(), set.end(), SquareTriangle{m, 0}) != set.end()) columns.push_back(i);
  }
  return columns;
}

TEST(PixelSquareSets, ExactAnswersOfSliversAndOfTrianglesAcrossTheEyePlane) {
  // 16x12: column lines at x = k/6 - 4/3, row lines at y = 1 - k/6.
  TestScene scene;
  scene.width = 16;
  scene.height = 12;
  // A sliver along row 5 (0 < y < 1/6) with its vertices off the image: every square of the row
  // holds it though it covers no corner and none of its vertices lies in a square.
  scene.meshes.push_back(
      image_triangle({0.0}, {{{{-3.0, 0.05, 2}, {3.0, 0.06, 2}, {3.0, 0.07, 2}}}}));
  // Across the eye plane: two vertices on the line x = 0.05 before the eye, one behind it whose
  // edges cross the eye plane at x > 0: R is the part of the half-plane x >= 0.05 within the wedge
  // of those two edges, which spans the image's height: columns 8 (0 < x < 1/6) to 15 of every row.
  scene.meshes.push_back(
      moving_triangle({0.0}, {{Vec(0.05, -5, 1), Vec(0.05, 5, 1), Vec(1, 0, -1)}}));
  // Behind the eye: R is empty.
  scene.meshes.push_back(
      moving_triangle({0.0}, {{Vec(-1, -1, -2), Vec(1, -1, -2), Vec(0, 1, -2)}}));
  // A tiny triangle inside square (3, 2): x in (-5/6, -2/3), y in (1/2, 2/3).
  scene.meshes.push_back(
      image_triangle({0.0}, {{{{-0.80, 0.55, 4}, {-0.70, 0.56, 4}, {-0.75, 0.62, 4}}}}));
  PixelSquareSets sets(scene.input(), 0.0);
  std::vector<int> all(16), right(8);
  for (int i = 0; i < 16; ++i) all[size_t(i)] = i;
  for (int i = 0; i < 8; ++i) right[size_t(i)] = 8 + i;
  for (int j = 0; j < 12; ++j) {
    EXPECT_EQ(columns_holding(sets, 0, j), j == 5 ? all : std::vector<int>{}) << "row " << j;
    EXPECT_EQ(columns_holding(sets, 1, j), right) << "row " << j;
    EXPECT_EQ(columns_holding(sets, 2, j), std::vector<int>{}) << "row " << j;
    EXPECT_EQ(columns_holding(sets, 3, j), j == 2 ? std::vector<int>{3} : std::vector<int>{})
        << "row " << j;
  }
  EXPECT_TRUE(sets.audit().empty());
}

TEST(PixelSquareSets, StaticSceneEmitsNoEvents) {
  TestScene scene = synthetic_scene();
  for (test::OwnedMesh& m : scene.meshes) {
    // Every key at the first key's positions.
    for (size_t k = 1; k < m.times.size(); ++k)
      for (size_t v = 0; v < m.vertex_count; ++v)
        m.positions[k * m.vertex_count + v] = m.positions[v];
    m.is_static = true;
  }
  PixelSquareSets sets(scene.input(), 0.0);
  expect_matches_brute_force(sets, random_times(0.0, 5.0, 10, 5));
  const SquareStats stats = sets.stats();
  EXPECT_EQ(stats.events.total(), 0u);
  EXPECT_EQ(stats.certificates_scheduled, 0u);
  EXPECT_GT(stats.pixel_entries, 0u);
}

}  // namespace
}  // namespace kinray
