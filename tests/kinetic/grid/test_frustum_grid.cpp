// The kinetic grid of frusta: exact-answer cases (a depth swap, an edge over a pixel centre, a
// vertex over row planes, a plane through the eye, geometry passing behind the camera, objects
// appearing and disappearing) and property tests against a brute-force sign-rule reference, with
// the audit on: every advance re-checks every record, slot, interval, pixel set and certificate.
#include <random>

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include "kinetic/grid/frustum_grid.h"
#include "kinetic/grid/grid_scene.h"
#include "tests/kinetic/grid/grid_test_scenes.h"

namespace kinray {
namespace {

using test::at_depth;
using test::OwnedMesh;
using test::TestScene;
using test::Vec;

FrustumGridConfig audited(DepthSortKind sort = DepthSortKind::kList, int bands = 2) {
  FrustumGridConfig config;
  config.threads = 2;
  config.bands = bands;
  config.sort = sort;
  config.audit = true;
  return config;
}

// Advances through `times`, checking the grid against the reference at each; returns the totals.
test::Comparison run_against_brute_force(FrustumGrid& grid, const GridInput& in,
                                         const std::vector<double>& times) {
  test::Comparison total;
  for (double t : times) {
    grid.advance_to(t);
    const test::Comparison c = test::compare_with_brute_force(grid, in);
    EXPECT_EQ(c.real, 0u) << "t = " << t;
    total.covered += c.covered;
    total.ties += c.ties;
    total.real += c.real;
  }
  return total;
}

std::vector<double> even_times(double a, double b, int n) {
  std::vector<double> times;
  for (int k = 0; k <= n; ++k) times.push_back(a + (b - a) * k / n);
  return times;
}

class GridSorts : public ::testing::TestWithParam<DepthSortKind> {};
INSTANTIATE_TEST_SUITE_P(AllSorts, GridSorts,
                         ::testing::Values(DepthSortKind::kList, DepthSortKind::kTournament,
                                           DepthSortKind::kHeap),
                         [](const auto& param) { return std::string(depth_sort_name(param.param)); });

// Two triangles parallel to the image plane; B moves in depth from z = 3 to z = 1 and passes A
// (z = 2) at exactly t* = 0.5. Its image does not change, so every pixel of B swaps once.
TEST_P(GridSorts, TwoTrianglesSwapDepthAtTheKnownTime) {
  TestScene scene;
  scene.meshes.push_back(test::moving_triangle(
      {0.0}, {{at_depth(-1.5, -1, 2), at_depth(1.5, -1, 2), at_depth(0, 1.5, 2)}}));
  auto b_at = [](double z) {
    return std::array<Vec, 3>{at_depth(-0.8, -0.6, z), at_depth(0.8, -0.6, z), at_depth(0, 0.7, z)};
  };
  scene.meshes.push_back(test::moving_triangle({0.0, 1.0}, {b_at(3), b_at(1)}));
  const GridInput in = scene.input();
  FrustumGrid grid(in, 0.0, audited(GetParam()));

  size_t pixels_of_b = 0;
  for (int j = 0; j < scene.height; ++j)
    for (int i = 0; i < scene.width; ++i) pixels_of_b += test::brute_front(in, i, j, 0.9).mesh == 1;
  ASSERT_GT(pixels_of_b, 100u);

  grid.advance_to(0.5 - 1e-9);
  EXPECT_EQ(grid.stats().events.swap, 0u);
  std::vector<uint32_t> object(in.rays.pixel_count()), prim(object.size());
  std::vector<float> depth(object.size());
  for (int j = 0; j < scene.height; ++j)
    for (int i = 0; i < scene.width; ++i)
      if (test::brute_front(in, i, j, 0.9).mesh == 1) {
        ASSERT_TRUE(grid.front(i, j));
        EXPECT_EQ(grid.front(i, j)->mesh, 0u);
      }
  grid.advance_to(0.5 + 1e-9);
  EXPECT_EQ(grid.stats().events.swap, pixels_of_b);  // one swap per pixel, exactly at t*
  grid.read_out(object, prim, depth);
  for (int j = 0; j < scene.height; ++j)
    for (int i = 0; i < scene.width; ++i) {
      const size_t p = size_t(j) * size_t(scene.width) + size_t(i);
      if (test::brute_front(in, i, j, 0.9).mesh == 1) {
        EXPECT_EQ(object[p], 1u);
        EXPECT_NEAR(depth[p], 2.0 - 2e-9, 1e-6);
      }
    }
  grid.advance_to(1.0);
  EXPECT_EQ(grid.stats().events.swap, pixels_of_b);
  EXPECT_EQ(grid.stats().events.boundary, 0u);  // B's image stands still
  EXPECT_EQ(grid.stats().events.vertex_row, 0u);
  EXPECT_EQ(test::compare_with_brute_force(grid, in).real, 0u);
}

// A rectangle (two triangles) at depth 2 slides right at 0.4 image units per second: every
// boundary of every row moves by exactly 0.4, so the boundary events are countable (the diagonal
// is one edge of both triangles: one event per pixel centre it crosses, which passes the pixel
// from one triangle to the other), and its right edge reaches a chosen pixel centre at a known
// time.
TEST_P(GridSorts, EdgeSweepsOverPixelCentresAtKnownTimes) {
  TestScene scene;
  const double z = 2, X0 = -1, X1 = 0.3, Y0 = -0.6, Y1 = 0.6, V = 0.8;
  OwnedMesh rect;
  rect.times = {0.0, 1.0};
  rect.vertex_count = 4;
  for (double shift : {0.0, V})
    for (const Vec& p : {Vec(X0 + shift, Y0, z), Vec(X1 + shift, Y0, z), Vec(X1 + shift, Y1, z),
                         Vec(X0 + shift, Y1, z)})
      rect.positions.push_back(p);
  rect.triangles = {{0, 1, 2}, {0, 2, 3}};
  scene.meshes.push_back(rect);
  const GridInput in = scene.input();
  const PixelRays& rays = in.rays;

  // Expected crossings: every boundary x0 of every row the rectangle meets moves to x0 + 0.4.
  const double shift = V / z;
  auto crossed = [&](double x0) {
    int n = 0;
    for (int i = 0; i < rays.width; ++i) n += rays.x(i) > x0 && rays.x(i) <= x0 + shift;
    return n;
  };
  uint64_t expected = 0;
  int middle_row = -1;
  for (int j = 0; j < rays.height; ++j) {
    const double y = rays.y(j);
    if (!(y > Y0 / z && y < Y1 / z)) continue;
    if (middle_row < 0 && y < 0.05) middle_row = j;
    const double x_diagonal = X0 / z + (y * z - Y0) / (Y1 - Y0) * (X1 - X0) / z;
    expected += crossed(X0 / z) + crossed(x_diagonal) + crossed(X1 / z);
  }

  // The first column right of the right edge at t = 0, and the time the edge reaches it.
  int column = 0;
  while (rays.x(column) <= X1 / z) ++column;
  const double t_hit = (rays.x(column) * z - X1) / V;
  ASSERT_GT(t_hit, 0.01);

  FrustumGrid grid(in, 0.0, audited(GetParam()));
  grid.advance_to(t_hit - 1e-9);
  EXPECT_FALSE(grid.front(column, middle_row));
  grid.advance_to(t_hit + 1e-9);
  ASSERT_TRUE(grid.front(column, middle_row));
  EXPECT_EQ(grid.front(column, middle_row)->triangle, 0u);
  grid.advance_to(1.0);
  const GridStats stats = grid.stats();
  EXPECT_EQ(stats.events.boundary, expected);
  EXPECT_EQ(stats.events.vertex_row, 0u);
  EXPECT_EQ(stats.events.orientation, 0u);
  EXPECT_EQ(stats.events.flightplan, 1u);  // the motion stops at the last key
  EXPECT_EQ(test::compare_with_brute_force(grid, in).real, 0u);
}

// Edge ids: the two triangles of a mesh edge share one, a third triangle on the same edge (a
// non-manifold "book" of three pages) gets its own, and the ends are in increasing id order.
TEST(GridScene, TrianglesOfAnEdgeShareItsId) {
  TestScene scene;
  OwnedMesh book;
  book.vertex_count = 5;
  book.positions = {at_depth(0, -0.5, 2), at_depth(0, 0.5, 2), at_depth(0.5, 0, 2),
                    at_depth(-0.5, 0, 2), at_depth(0.3, 0.2, 3)};
  book.triangles = {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}};
  book.is_static = true;
  scene.meshes.push_back(book);
  const GridScene gs(scene.input());
  // Edge 0 of every page runs between vertices 0 and 1.
  EXPECT_EQ(gs.edge_of_triangle(0, 0), gs.edge_of_triangle(1, 0));
  EXPECT_NE(gs.edge_of_triangle(2, 0), gs.edge_of_triangle(0, 0));
  EXPECT_EQ(gs.edge_vertices(gs.edge_of_triangle(1, 0)), (std::array<uint32_t, 2>{0, 1}));
  EXPECT_EQ(gs.edge_vertices(gs.edge_of_triangle(2, 0)), (std::array<uint32_t, 2>{0, 1}));
  // Edges 1 and 2 of the pages are their own: 2 + 2 x 3 + 1 ids in all.
  EXPECT_EQ(gs.edge_count(), 8u);
  EXPECT_EQ(gs.edge_vertices(gs.edge_of_triangle(0, 2)), (std::array<uint32_t, 2>{0, 2}));
}

// A seam: a mesh edge written twice, with vertices of the same flightplan (as exporters write
// skinned models' texture seams). The grid welds them: its two sides share their corners and
// their edge; a vertex equal to another at one key only, and a triangle welding would give one
// vertex twice, keep their ids.
TEST(GridScene, SeamsAreWelded) {
  TestScene scene;
  OwnedMesh seam;
  seam.times = {0.0, 1.0};
  seam.vertex_count = 7;
  for (double u : {0.0, 0.3}) {
    const Vec p = at_depth(0 + u, -0.5, 2), q = at_depth(0, 0.5, 2 + u);
    // 3 and 4 are 1 and 0 again; 5 is 2 at the first key only; 6 is 2 again
    for (const Vec& v : {p, q, at_depth(0.5, 0, 2), q, p,
                         u == 0 ? at_depth(0.5, 0, 2) : at_depth(-0.5, 0, 2), at_depth(0.5, 0, 2)})
      seam.positions.push_back(v);
  }
  seam.triangles = {{0, 1, 2}, {3, 4, 5}, {0, 2, 6}};
  scene.meshes.push_back(seam);
  const GridScene gs(scene.input());
  EXPECT_EQ(gs.triangle_vertices(0), (std::array<uint32_t, 3>{0, 1, 2}));
  EXPECT_EQ(gs.triangle_vertices(1), (std::array<uint32_t, 3>{1, 0, 5}));
  EXPECT_EQ(gs.triangle_vertices(2), (std::array<uint32_t, 3>{0, 2, 6}));  // 2 and 6: one point
  EXPECT_EQ(gs.edge_of_triangle(0, 0), gs.edge_of_triangle(1, 0));         // the seam: one edge
  EXPECT_TRUE(gs.triangles_of_vertex(3).empty());
  EXPECT_TRUE(gs.triangles_of_vertex(4).empty());
}

// A fold across a seam (the two sides overlap on the screen and turn through each other) runs
// like the same fold across a shared edge: the same events, and the fronts of brute force.
// The seam's sides used to be ordered by the general depth certificate, whose roots on the edge
// itself fired swaps ulps before the coverage events that end them.
TEST_P(GridSorts, AFoldAcrossASeamRunsLikeASharedEdge) {
  GridEventCounts counts[2];
  for (const bool split : {false, true}) {
    TestScene scene;
    OwnedMesh fold;
    fold.times = {0.0, 1.0};
    fold.vertex_count = split ? 6 : 4;
    for (double u : {0.0, 1.0}) {
      // the spine sweeps over pixel centres, where both flaps leave or enter a pixel at once
      const Vec p = at_depth(-0.2 + 0.3 * u, -0.6, 2), q = at_depth(0.1 + 0.2 * u, 0.6, 2.2);
      // both flaps on the same side of the spine p q: a fold, whose far flap turns through the
      // near one
      const Vec a = at_depth(0.6, 0.1, 2.1), b = at_depth(0.5 - 0.3 * u, -0.1, 1.6 + 1.0 * u);
      for (const Vec& v : split ? std::vector<Vec>{p, q, a, q, p, b} : std::vector<Vec>{p, q, a, b})
        fold.positions.push_back(v);
    }
    fold.triangles = split ? std::vector<std::array<uint32_t, 3>>{{0, 1, 2}, {3, 4, 5}}
                           : std::vector<std::array<uint32_t, 3>>{{0, 1, 2}, {1, 0, 3}};
    scene.meshes.push_back(fold);
    const GridInput in = scene.input();
    FrustumGrid grid(in, 0.0, audited(GetParam()));
    const test::Comparison c = run_against_brute_force(grid, in, even_times(0, 1, 40));
    EXPECT_GT(c.covered, 500u);
    counts[split] = grid.stats().events;
  }
  EXPECT_GT(counts[0].swap, 0u);
  EXPECT_EQ(counts[1].swap, counts[0].swap);
  EXPECT_EQ(counts[1].total(), counts[0].total());  // welded, every event the same
}

// Three pages on one spine (a non-manifold edge) slide and turn across the image, the spine over
// many pixel centres: two pages share the spine's boundaries, the third has its own, and every
// pixel they pass hands over between them exactly.
TEST_P(GridSorts, PagesOfABookHandOverTheirSharedSpine) {
  TestScene scene;
  OwnedMesh book;
  book.times = {0.0, 1.0};
  book.vertex_count = 5;
  for (double u : {0.0, 0.6})
    for (const Vec& p : {at_depth(-0.6 + u, -0.5, 2), at_depth(-0.4 + u, 0.5, 2.2),
                         at_depth(-0.1 + u, 0.1, 2.1 + u), at_depth(-0.9 + u, 0.05, 1.9),
                         at_depth(-0.3 + u, -0.2, 3 - u)})
      book.positions.push_back(p);
  book.triangles = {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}};
  scene.meshes.push_back(book);
  const GridInput in = scene.input();
  FrustumGrid grid(in, 0.0, audited(GetParam(), 3));
  const test::Comparison c = run_against_brute_force(grid, in, even_times(0, 1, 25));
  EXPECT_GT(c.covered, 1000u);
  EXPECT_GT(grid.stats().events.boundary, 50u);
}

// A vertex moving down the image crosses a known set of row planes.
TEST_P(GridSorts, VertexCrossesRowPlanes) {
  TestScene scene;
  const double z = 2;
  scene.meshes.push_back(test::moving_triangle(
      {0.0, 1.0}, {{at_depth(-1, -0.5, z), at_depth(1, -0.5, z), at_depth(0.1, 0.2, z)},
                   {at_depth(-1, -0.5, z), at_depth(1, -0.5, z), at_depth(0.1, 0.7, z)}}));
  const GridInput in = scene.input();
  uint64_t rows_crossed = 0;
  for (int j = 0; j < scene.height; ++j) rows_crossed += in.rays.y(j) > 0.2 && in.rays.y(j) < 0.7;
  FrustumGrid grid(in, 0.0, audited(GetParam(), 3));
  const test::Comparison c = run_against_brute_force(grid, in, even_times(0, 1, 20));
  EXPECT_GT(c.covered, 0u);
  EXPECT_EQ(grid.stats().events.vertex_row, rows_crossed);
}

// An edge parallel to the rows (both ends share y and z) sweeps across a row plane: both its
// vertices cross it at one instant, while the edge lies in the plane. The record born there
// covers 16 columns at once; rounding may make the edge's own sign flip an ulp later than the
// vertex-row event, which must not leave the row uncovered.
TEST_P(GridSorts, EdgeParallelToTheRowsCrossesARowPlane) {
  TestScene scene;
  scene.width = scene.height = 32;
  auto key = [](double v) {
    return std::array<Vec, 3>{at_depth(-0.5, v, 3), at_depth(0.5, v, 3), at_depth(0.1, -0.5, 2)};
  };
  scene.meshes.push_back(test::moving_triangle({0.0, 1.0}, {key(0.3), key(0.6)}));
  const GridInput in = scene.input();
  FrustumGrid grid(in, 0.0, audited(GetParam(), 1));
  // Row 8 (y = 15/32) is crossed at t = 9/16; 0.625 is just after.
  run_against_brute_force(grid, in, {0.5, 0.5625, 0.5625 + 1e-15, 0.57, 0.625, 0.75, 1.0});
  grid.advance_to(1.0);
  EXPECT_GE(grid.stats().events.vertex_row, 2u);
}

// A triangle translating along -z through the eye plane: the sign rule decides what is seen
// while it straddles the eye; once fully behind, nothing is.
TEST_P(GridSorts, TrianglePassingBehindTheCamera) {
  TestScene scene;
  auto key = [](double dz) {
    return std::array<Vec, 3>{Vec(-1, -1, 2 + dz), Vec(1.2, -0.8, 2.5 + dz), Vec(0.1, 1.1, 1.7 + dz)};
  };
  scene.meshes.push_back(test::moving_triangle({0.0, 1.0}, {key(0), key(-4.0)}));
  const GridInput in = scene.input();
  FrustumGrid grid(in, 0.0, audited(GetParam()));
  const test::Comparison c = run_against_brute_force(grid, in, even_times(0, 1, 40));
  EXPECT_GT(c.covered, 1000u);
  for (int j = 0; j < scene.height; ++j)
    for (int i = 0; i < scene.width; ++i) EXPECT_FALSE(grid.front(i, j));
  EXPECT_GT(grid.stats().events.boundary, 0u);
}

// A static triangle whose plane contains the eye covers nothing; one whose plane sweeps through
// the eye (det(v0, v1, v2) = 2 - 4t, zero at t = 0.5, when its image is the slanted line through
// v0 and v1) fires orientation events and stays exact.
TEST_P(GridSorts, EdgeOnTriangleAndPlaneThroughTheEye) {
  TestScene scene;
  scene.meshes.push_back(
      test::moving_triangle({0.0}, {{Vec(0.2, 0, 2), Vec(0.1, 1, 1), Vec(0.3, -1, 3)}}));
  {
    FrustumGrid grid(scene.input(), 0.0, audited(GetParam()));
    for (int j = 0; j < scene.height; ++j)
      for (int i = 0; i < scene.width; ++i) EXPECT_FALSE(grid.front(i, j));
  }
  scene.meshes.push_back(test::moving_triangle(
      {0.0, 1.0}, {{Vec(-1, -0.5, 1), Vec(1, 0.5, 1), Vec(-1, 0.5, 1.5)},
                   {Vec(-1, -0.5, 1), Vec(1, 0.5, 1), Vec(1, -0.5, 1.5)}}));
  const GridInput in = scene.input();
  FrustumGrid grid(in, 0.0, audited(GetParam()));
  const test::Comparison c = run_against_brute_force(grid, in, even_times(0, 1, 50));
  EXPECT_GT(c.covered, 500u);
  EXPECT_GT(grid.stats().events.orientation, 0u);
}

// Zero-area slivers (three collinear vertices, as BART's kitchen has) cover nothing, at any time:
// their vertices share x and z exactly, so det(v0, v1, v2) is zero, though formed in double it
// was rounding noise that let a sliver claim pixels at infinite depth (kitchen, t = 7.18 s).
TEST_P(GridSorts, ZeroAreaSliversCoverNothing) {
  TestScene scene;
  scene.meshes.push_back(test::moving_triangle(
      {0.0}, {{at_depth(-9, -9, 6), at_depth(9, -9, 6), at_depth(0, 9, 6)}}));
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int k = 0; k < 60; ++k) {
    std::array<Vec, 3> from, to;
    const double x0 = 1.3 * u(rng), z0 = 2.5 + u(rng), x1 = 1.3 * u(rng), z1 = 2.5 + u(rng);
    for (int v = 0; v < 3; ++v) {
      from[size_t(v)] = Vec(x0 * z0 / 3.7, u(rng) * z0, z0 * 1.1);
      to[size_t(v)] = Vec(x1 * z1 / 3.7, u(rng) * z1, z1 * 1.1);
    }
    scene.meshes.push_back(test::moving_triangle({0.0, 1.0}, {from, to}));
  }
  const GridInput in = scene.input();
  FrustumGrid grid(in, 0.0, audited(GetParam()));
  for (double t : even_times(0, 1, 40)) {
    grid.advance_to(t);
    size_t claimed = 0;
    for (int j = 0; j < scene.height; ++j)
      for (int i = 0; i < scene.width; ++i) {
        const auto hit = grid.front(i, j);
        ASSERT_TRUE(hit.has_value()) << "pixel (" << i << ", " << j << ") at t = " << t;
        claimed += hit->mesh != 0;
      }
    EXPECT_EQ(claimed, 0u) << "pixels a sliver claims at t = " << t;
  }
}

// Triangles that flatten into slivers at a key, stay so over the next key interval (O the zero
// polynomial there) and open again: they cover nothing while flat, and their kept orientation
// signs follow. Positions interpolated to the key land within an ulp of it, so O at the end of
// the interval before is rounding, often with no root: the kitchen (t = 6.75 s) kept that
// interval's sign into the flat one, which the audit caught.
TEST_P(GridSorts, TrianglesFlatForAWholeKeyIntervalCoverNothingThen) {
  TestScene scene;
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int k = 0; k < 24; ++k) {
    std::array<Vec, 3> open, flat, flat_moved;
    const double cx = 0.9 * u(rng), cy = 0.5 * u(rng), x = 0.9 * u(rng), z = 2.2 + 0.3 * u(rng);
    for (int v = 0; v < 3; ++v) {
      open[size_t(v)] = at_depth(cx + 0.4 * u(rng), cy + 0.4 * u(rng), 2 + 0.5 * u(rng));
      flat[size_t(v)] = Vec(x * z, (0.6 * u(rng)) * z, z);
      flat_moved[size_t(v)] = Vec(x * z + 0.1, (0.6 * u(rng)) * z, z + 0.2);
    }
    scene.meshes.push_back(test::moving_triangle({0.0, 1.0, 2.0, 3.0}, {open, flat, flat_moved, open}));
  }
  const GridInput in = scene.input();
  FrustumGrid grid(in, 0.0, audited(GetParam()));
  auto covered = [&] {
    size_t n = 0;
    for (int j = 0; j < scene.height; ++j)
      for (int i = 0; i < scene.width; ++i) n += grid.front(i, j).has_value();
    return n;
  };
  for (double t : {0.25, 0.5, 0.9, 1.0, 1.3, 1.5, 1.99, 2.0, 2.1, 2.5, 3.0}) {
    grid.advance_to(t);  // audited at every event
    if (t >= 1.0 && t < 2.0) {
      EXPECT_EQ(covered(), 0u) << "t = " << t;
    }
    if (t <= 0.5 || t >= 2.5) {
      EXPECT_GT(covered(), 100u) << "t = " << t;
    }
  }
}

// Objects inserted and removed mid-run, over a static background.
TEST_P(GridSorts, ObjectsAppearAndDisappear) {
  TestScene scene;
  scene.meshes.push_back(test::moving_triangle(
      {0.0}, {{at_depth(-2, -2, 5), at_depth(2, -2, 5), at_depth(0, 2, 5)}}));
  OwnedMesh visitor = test::moving_triangle(
      {0.0, 1.0}, {{at_depth(-0.9, -0.5, 2), at_depth(0.2, -0.6, 3), at_depth(-0.3, 0.6, 2.5)},
                   {at_depth(-0.2, -0.5, 2), at_depth(0.9, -0.4, 3), at_depth(0.4, 0.7, 2.5)}});
  visitor.appear = 0.3;
  visitor.disappear = 0.7;
  scene.meshes.push_back(visitor);
  const GridInput in = scene.input();
  FrustumGrid grid(in, 0.0, audited(GetParam()));
  run_against_brute_force(grid, in, {0.1, 0.3, 0.31, 0.5, 0.69, 0.7, 0.9, 1.0});
  const GridStats stats = grid.stats();
  EXPECT_EQ(stats.events.insert, 1u);
  EXPECT_EQ(stats.events.remove, 1u);
  for (int j = 0; j < scene.height; ++j)
    for (int i = 0; i < scene.width; ++i) {
      const auto hit = grid.front(i, j);
      EXPECT_TRUE(!hit || hit->mesh == 0u) << i << ", " << j;
    }
}

// A static mesh emits no coverage events; a moving one cuts through it (interpenetration).
TEST_P(GridSorts, StaticAndMovingInterpenetrate) {
  TestScene scene;
  OwnedMesh wall;
  wall.vertex_count = 4;
  wall.positions = {Vec(-3, -2, 3), Vec(3, -2, 3), Vec(3, 2, 4), Vec(-3, 2, 4)};
  wall.triangles = {{0, 1, 2}, {0, 2, 3}};
  wall.is_static = true;
  scene.meshes.push_back(wall);
  scene.meshes.push_back(test::moving_triangle(
      {0.0, 0.5, 1.0}, {{Vec(-1.5, -1, 2), Vec(1, -0.8, 5), Vec(0, 1.2, 3)},
                        {Vec(-1, -1.2, 3.5), Vec(1.4, -0.6, 2.5), Vec(0.2, 1.0, 4)},
                        {Vec(-1.2, -0.7, 2.2), Vec(0.8, -1.1, 4.5), Vec(-0.3, 1.4, 2.6)}}));
  const GridInput in = scene.input();
  FrustumGrid grid(in, 0.0, audited(GetParam()));
  const test::Comparison c = run_against_brute_force(grid, in, even_times(0, 1, 25));
  EXPECT_GT(c.covered, 1000u);
  const GridStats stats = grid.stats();
  EXPECT_GT(stats.events.swap, 0u);
  EXPECT_EQ(stats.events.flightplan, 2u);
}

struct RandomScene {
  TestScene scene;
  explicit RandomScene(uint32_t seed, int triangles = 8) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> xy(-1.5, 1.5), z(0.5, 4), dz(-3, 1);
    for (int k = 0; k < triangles; ++k) {
      const int keys = 2 + k % 3;
      std::vector<double> times;
      std::vector<std::array<Vec, 3>> positions;
      std::array<Vec, 3> p;
      for (Vec& v : p) v = Vec(xy(rng), xy(rng), z(rng));
      for (int key = 0; key < keys; ++key) {
        times.push_back(double(key) / (keys - 1));
        positions.push_back(p);
        const double drift = dz(rng);
        for (Vec& v : p) v += Vec(0.5 * xy(rng), 0.5 * xy(rng), drift + 0.3 * xy(rng));
      }
      scene.meshes.push_back(test::moving_triangle(times, positions));
    }
  }
};

// Random moving triangles (some pass behind the camera) against brute force at many times.
TEST_P(GridSorts, RandomMotionsAgreeWithBruteForce) {
  for (uint32_t seed : {1u, 2u, 3u}) {
    RandomScene r(seed);
    const GridInput in = r.scene.input();
    FrustumGrid grid(in, 0.0, audited(GetParam()));
    const test::Comparison c = run_against_brute_force(grid, in, even_times(0, 1, 30));
    EXPECT_GT(c.covered, 1000u) << "seed " << seed;
    EXPECT_LT(c.ties, c.covered / 1000 + 5) << "seed " << seed;
  }
}

// Degenerate image shapes: one column (the only slot is off), one row (bands of one row).
TEST(FrustumGrid, TinyImagesAgreeWithBruteForce) {
  for (const auto& [w, h] : std::vector<std::pair<int, int>>{{1, 1}, {2, 1}, {1, 3}, {5, 2}, {3, 7}}) {
    RandomScene r(9, 12);
    r.scene.width = w;
    r.scene.height = h;
    const GridInput in = r.scene.input();
    FrustumGrid grid(in, 0.0, audited(DepthSortKind::kList, std::min(h, 2)));
    const test::Comparison c = run_against_brute_force(grid, in, even_times(0, 1, 40));
    EXPECT_EQ(c.real, 0u) << w << "x" << h;
  }
}

// A regular octahedron of radius `scale` whose keyed poses turn by 0.7 rad per key about a
// tilted axis while its centre moves from `start` by `step` per key. Between keys the vertices
// blend linearly, so every instant is the octahedron under one regular linear map: a convex
// solid, which back_face_cull_sign proves. `outward`: the triangles wind with outward normals.
OwnedMesh tumbling_octahedron(double scale, const Vec& start, const Vec& step, bool outward = true,
                              int keys = 5) {
  const Vec axes[6] = {Vec::UnitX(), -Vec::UnitX(), Vec::UnitY(), -Vec::UnitY(), Vec::UnitZ(), -Vec::UnitZ()};
  OwnedMesh m;
  m.vertex_count = 6;
  m.times.clear();
  for (int k = 0; k < keys; ++k) {
    m.times.push_back(double(k) / (keys - 1));
    const Eigen::Matrix3d turn = Eigen::AngleAxisd(0.7 * k, Vec(0.3, 1, 0.2).normalized()).toRotationMatrix();
    for (const Vec& a : axes) m.positions.push_back(start + double(k) * step + scale * (turn * a));
  }
  for (uint32_t sx : {0u, 1u})
    for (uint32_t sy : {2u, 3u})
      for (uint32_t sz : {4u, 5u}) {
        // (+x, +y, +z) winds outward; each negative axis flips the winding.
        const bool flip = ((sx & 1) ^ (sy & 1) ^ (sz & 1)) != (outward ? 0u : 1u);
        m.triangles.push_back(flip ? std::array<uint32_t, 3>{sx, sz, sy} : std::array<uint32_t, 3>{sx, sy, sz});
      }
  return m;
}

// The same mesh with a second component out of view (behind the eye), a small octahedron wound
// the other way: the two orientations disagree, so culling is declined while every frame stays
// the same.
OwnedMesh with_opposite_component_behind_the_eye(OwnedMesh m, bool outward) {
  const OwnedMesh extra = tumbling_octahedron(0.1, Vec(0, 0, -3), Vec::Zero(), !outward, int(m.times.size()));
  std::vector<Vec> positions;
  for (size_t k = 0; k < m.times.size(); ++k) {
    for (size_t v = 0; v < m.vertex_count; ++v) positions.push_back(m.positions[k * m.vertex_count + v]);
    for (size_t v = 0; v < extra.vertex_count; ++v) positions.push_back(extra.positions[k * extra.vertex_count + v]);
  }
  for (auto tri : extra.triangles) {
    for (uint32_t& v : tri) v += uint32_t(m.vertex_count);
    m.triangles.push_back(tri);
  }
  m.positions = std::move(positions);
  m.vertex_count += extra.vertex_count;
  return m;
}

// Back-face culling of a closed solid: the octahedron's faces turning away lose their records
// and the ones turning to the eye get them, with the audit on; a triangle flies through it. The
// frames equal the brute-force reference (which sees every face) and the unculled grid's.
TEST_P(GridSorts, BackFaceCullingOfAClosedSolidAgreesWithBruteForce) {
  for (const bool outward : {true, false}) {
    SCOPED_TRACE(outward ? "outward" : "inward");
    TestScene scene;
    scene.meshes.push_back(tumbling_octahedron(1.2, Vec(-0.4, 0.1, 4.0), Vec(0.2, -0.05, 0.3), outward));
    scene.meshes.push_back(test::moving_triangle(
        {0.0, 1.0}, {{at_depth(-1.2, -0.5, 3.0), at_depth(-0.6, -0.4, 5.5), at_depth(-0.9, 0.6, 4.0)},
                     {at_depth(0.9, -0.5, 5.0), at_depth(1.1, -0.4, 3.5), at_depth(0.7, 0.5, 4.5)}}));
    const GridInput in = scene.input();
    EXPECT_EQ(GridScene(in).cull_sign(0), outward ? -1 : 1);
    EXPECT_EQ(GridScene(in).cull_sign(1), 0);
    FrustumGrid grid(in, 0.0, audited(GetParam()));
    TestScene plain = scene;
    plain.meshes[0] = with_opposite_component_behind_the_eye(plain.meshes[0], outward);
    ASSERT_EQ(GridScene(plain.input()).cull_sign(0), 0);
    const GridInput in_plain = plain.input();
    FrustumGrid unculled(in_plain, 0.0, audited(GetParam()));
    const test::Comparison c = run_against_brute_force(grid, in, even_times(0, 1, 40));
    EXPECT_GT(c.covered, 2000u);
    EXPECT_LT(c.ties, c.covered / 1000 + 5);
    unculled.advance_to(1.0);
    EXPECT_EQ(test::fronts(grid), test::fronts(unculled));  // the extra triangles are never in view
    const GridStats s = grid.stats(), u = unculled.stats();
    EXPECT_EQ(s.meshes_culling, 1u);
    EXPECT_EQ(u.meshes_culling, 0u);
    EXPECT_GE(s.triangles_culled, 1u);  // some faces turned away, some to the eye, at t = 1
    EXPECT_LE(s.triangles_culled, 7u);
    EXPECT_GT(s.events.orientation, 0u);  // faces turned on and off
    EXPECT_LT(s.events.boundary, u.events.boundary);
    EXPECT_LT(s.pixel_entries, u.pixel_entries);
  }
}

// Culling is declined wherever a back face could be the first hit: an open mesh, the eye inside
// a segment's bounding box (here inside the solid: every ray sees its inner faces). The solids
// that pass through themselves between keys, or are not star-shaped, are in
// test_back_face_culling.cpp.
TEST(FrustumGrid, BackFaceCullingStaysOffWhereItIsNotSound) {
  TestScene open;
  open.meshes.push_back(tumbling_octahedron(1.2, Vec(0, 0, 4), Vec(0, 0, 0.2)));
  EXPECT_EQ(GridScene(open.input()).cull_sign(0), -1);
  open.meshes[0].triangles.pop_back();
  EXPECT_EQ(GridScene(open.input()).cull_sign(0), 0);

  TestScene approaching;  // outside at first, the last segment's box holds the eye
  approaching.meshes.push_back(tumbling_octahedron(1.0, Vec(0, 0, 4), Vec(0, 0, -0.9)));
  EXPECT_EQ(GridScene(approaching.input()).cull_sign(0), 0);

  TestScene around;  // the eye inside the solid
  around.meshes.push_back(tumbling_octahedron(8.0, Vec(0.3, -0.2, 0.5), Vec(0.1, 0, 0.1)));
  const GridInput in = around.input();
  EXPECT_EQ(GridScene(in).cull_sign(0), 0);
  FrustumGrid grid(in, 0.0, audited());
  const test::Comparison c = run_against_brute_force(grid, in, even_times(0, 1, 10));
  // Every ray hits the inner faces (but for a centre ray grazing an edge of the octahedron).
  EXPECT_GT(c.covered, 11 * size_t(around.width) * size_t(around.height) * 99 / 100);
  EXPECT_EQ(grid.stats().meshes_culling, 0u);
}

GridEventCounts geometric(const GridStats& s) { return s.events; }
bool same_counts(const GridEventCounts& a, const GridEventCounts& b) {
  return a.boundary == b.boundary && a.vertex_row == b.vertex_row &&
         a.orientation == b.orientation && a.swap == b.swap && a.flightplan == b.flightplan &&
         a.insert == b.insert && a.remove == b.remove;
}

// The frames and the event counts depend neither on the band split nor on the depth sort's
// kind for coverage events, nor on how many frames are read out.
TEST(FrustumGrid, IndependentOfBandsAndFrameCount) {
  RandomScene r(42, 10);
  const GridInput in = r.scene.input();
  FrustumGridConfig one;
  one.threads = 1;
  one.bands = 1;
  FrustumGridConfig five = one;
  five.threads = 2;
  five.bands = 5;
  FrustumGrid a(in, 0.0, one), b(in, 0.0, five), dense(in, 0.0, one);
  for (int k = 1; k <= 8; ++k) {
    const double t = k / 8.0;
    for (int f = 1; f <= 16; ++f) dense.advance_to((k - 1 + f / 16.0) / 8.0);
    a.advance_to(t);
    b.advance_to(t);
    dense.advance_to(t);
    EXPECT_EQ(test::fronts(a), test::fronts(b)) << "t = " << t;
    EXPECT_EQ(test::fronts(a), test::fronts(dense)) << "t = " << t;
  }
  EXPECT_TRUE(same_counts(geometric(a.stats()), geometric(b.stats())));
  EXPECT_TRUE(same_counts(geometric(a.stats()), geometric(dense.stats())));
  EXPECT_GT(a.stats().events.total(), 100u);
}

TEST(FrustumGrid, RejectsTimeGoingBackAndBadInput) {
  TestScene scene;
  scene.meshes.push_back(test::moving_triangle({0.0}, {{Vec(0, 0, 1), Vec(1, 0, 1), Vec(0, 1, 1)}}));
  FrustumGrid grid(scene.input(), 0.5);
  EXPECT_THROW(grid.advance_to(0.25), std::invalid_argument);
  TestScene bad = scene;
  bad.meshes[0].triangles = {{0, 1, 7}};
  EXPECT_THROW(FrustumGrid(bad.input(), 0.0), std::invalid_argument);
}

}  // namespace
}  // namespace kinray
