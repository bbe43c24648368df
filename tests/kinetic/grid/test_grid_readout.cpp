// FrustumGrid::read_out against the straightforward read-out, bit for bit: per pixel the front
// triangle's plane from its vertices at now (FlightplanMesh::position) and TrianglePlane::depth.
// The scene reaches the read-out's less travelled paths: two triangles of one plane-cache slot side
// by side in every row, a static mesh (unblended positions) beside moving ones, odd covered runs,
// and a front triangle collapsed into the eye at a frame time (its depth there is no hit, so the
// nearest other member of the pixel's order is read out).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <span>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "kinetic/grid/frustum_grid.h"
#include "tests/kinetic/grid/grid_test_scenes.h"

namespace kinray {
namespace {

using test::at_depth;
using test::OwnedMesh;
using test::TestScene;
using test::Vec;

bool pierces(double z) { return std::isfinite(z) && z > 0; }

double depth_of(const GridInput& in, uint32_t mesh, uint32_t triangle, double t, int i, int j) {
  const auto p = test::triangle_at(in.meshes[mesh], triangle, t);
  return TrianglePlane(p[0], p[1], p[2]).depth(in.rays.x(i), in.rays.y(j));
}

bool same_bits(float a, float b) { return std::memcmp(&a, &b, sizeof a) == 0; }

TestScene readout_scene() {
  TestScene scene;
  scene.width = 97;  // odd: the last covered run of a row can end on the last column
  scene.height = 41;
  // Mesh 0: a rectangle at depth 3 split along its diagonal into triangles 0 and 2048, which share
  // a slot of the read-out's plane cache (2048 slots); between them 2047 small triangles behind
  // the camera, which are never hit. It drifts right, so its positions are blended.
  OwnedMesh rect;
  rect.times = {0.0, 1.0};
  const int hidden = 2047;
  for (double shift : {0.0, 0.4}) {
    for (const Vec& p : {at_depth(-1.1 + shift, -0.7, 3), at_depth(0.6 + shift, -0.7, 3),
                         at_depth(0.6 + shift, 0.8, 3), at_depth(-1.1 + shift, 0.8, 3)})
      rect.positions.push_back(p);
    for (int k = 0; k < hidden; ++k) {
      const double x = -1 + 2.0 * k / hidden;
      for (const Vec& p : {Vec(x, -0.5, -4), Vec(x + 0.01, -0.5, -4), Vec(x, -0.49, -4)}) rect.positions.push_back(p);
    }
  }
  rect.vertex_count = rect.positions.size() / 2;
  rect.triangles.push_back({0, 1, 2});
  for (uint32_t k = 0; k < uint32_t(hidden); ++k) rect.triangles.push_back({4 + 3 * k, 5 + 3 * k, 6 + 3 * k});
  rect.triangles.push_back({0, 2, 3});
  scene.meshes.push_back(rect);
  // Mesh 1: a static backdrop at depth 10 over the whole image.
  OwnedMesh backdrop;
  backdrop.positions = {at_depth(-3, -3, 10), at_depth(3, -3, 10), at_depth(3, 3, 10), at_depth(-3, 3, 10)};
  backdrop.vertex_count = 4;
  backdrop.triangles = {{0, 1, 2}, {0, 2, 3}};
  backdrop.is_static = true;
  scene.meshes.push_back(backdrop);
  // Mesh 2: a triangle whose image stands still while it shrinks into the eye (scale 1, then 0 at
  // the key t = 0.5) and comes back out: no event (nothing changes sign), so it stays the front of
  // its pixels, but at t = 0.5 it is the eye itself, exactly, and hits nothing.
  OwnedMesh collapsing;
  collapsing.times = {0.0, 0.5, 1.0};
  for (double s : {1.0, 0.0, 1.0})
    for (const Vec& p : {Vec(-0.5, -0.4, 1), Vec(0.3, -0.4, 1), Vec(-0.1, 0.5, 1)}) collapsing.positions.push_back(s * p);
  collapsing.vertex_count = 3;
  collapsing.triangles = {{0, 1, 2}};
  scene.meshes.push_back(collapsing);
  return scene;
}

TEST(GridReadout, IsTheFrontsPlaneDepthBitForBit) {
  const TestScene scene = readout_scene();
  const GridInput in = scene.input();
  for (const int threads : {1, 2}) {
    FrustumGridConfig config;
    config.threads = threads;
    FrustumGrid grid(in, 0.0, config);
    const size_t n = in.rays.pixel_count();
    std::vector<uint32_t> object(n), prim(n);
    std::vector<float> depth(n);
    size_t slot_neighbours = 0, fallbacks = 0, static_fronts = 0;
    for (const double t : {0.125, 0.375, 0.5, 0.625, 0.875}) {
      grid.advance_to(t);
      grid.read_out(object, prim, depth);
      for (int j = 0; j < in.rays.height; ++j)
        for (int i = 0; i < in.rays.width; ++i) {
          const size_t p = size_t(j) * size_t(in.rays.width) + size_t(i);
          const std::optional<GridHit> front = grid.front(i, j);
          if (!front) {
            EXPECT_EQ(object[p], kNoGridHit);
            EXPECT_EQ(prim[p], kNoGridHit);
            EXPECT_EQ(depth[p], std::numeric_limits<float>::infinity());
            continue;
          }
          static_fronts += front->mesh == 1;
          if (i > 0 && front->mesh == 0 && object[p - 1] == 0 && prim[p - 1] + front->triangle == 2048)
            ++slot_neighbours;
          const double z = depth_of(in, front->mesh, front->triangle, t, i, j);
          if (pierces(z)) {
            EXPECT_EQ(object[p], in.meshes[front->mesh].id) << i << "," << j << " t " << t;
            EXPECT_EQ(prim[p], front->triangle) << i << "," << j << " t " << t;
            EXPECT_TRUE(same_bits(depth[p], float(z))) << depth[p] << " vs " << float(z);
            continue;
          }
          // The front is no hit at t: another member that is, at its own exact depth.
          ++fallbacks;
          EXPECT_EQ(t, 0.5);
          EXPECT_EQ(front->mesh, 2u);
          ASSERT_NE(object[p], kNoGridHit);
          EXPECT_NE(object[p], 2u);
          const double zo = depth_of(in, object[p], prim[p], t, i, j);
          EXPECT_TRUE(pierces(zo));
          EXPECT_TRUE(same_bits(depth[p], float(zo)));
        }
    }
    EXPECT_GT(slot_neighbours, 20u);
    EXPECT_GT(fallbacks, 20u);
    EXPECT_GT(static_fronts, 100u);
  }
}

// Frames read out in batches, band by band (advance_and_read_out), are those of advance_to and
// read_out frame by frame, bit for bit, with the same events per frame, whatever the batches'
// lengths, the sort and the threads; the audit runs after each band's advance. The times include
// the one where a front collapses into the eye (its pixels read the next member out) and one
// repeated.
TEST(GridReadout, InBatchesIsFrameByFrameBitForBit) {
  const TestScene scene = readout_scene();
  const GridInput in = scene.input();
  const std::vector<double> times = {0.0625, 0.125, 0.25, 0.375, 0.5, 0.5, 0.625, 0.75, 0.875, 1.0};
  const size_t n = in.rays.pixel_count();
  for (const DepthSortKind sort :
       {DepthSortKind::kList, DepthSortKind::kTournament, DepthSortKind::kHeap})
    for (const int threads : {1, 2}) {
      FrustumGridConfig config;
      config.threads = threads;
      config.bands = 3;
      config.sort = sort;
      config.audit = true;
      FrustumGrid reference(in, 0.0, config);
      std::vector<std::vector<uint32_t>> object(times.size(), std::vector<uint32_t>(n)),
          prim = object;
      std::vector<std::vector<float>> depth(times.size(), std::vector<float>(n));
      std::vector<uint64_t> events;
      for (size_t f = 0; f < times.size(); ++f) {
        const uint64_t before = reference.event_count();
        reference.advance_to(times[f]);
        reference.read_out(object[f], prim[f], depth[f]);
        events.push_back(reference.event_count() - before);
      }
      EXPECT_GT(reference.event_count(), 0u);
      for (const size_t batch : {size_t(1), size_t(3), times.size()}) {
        FrustumGrid grid(in, 0.0, config);
        std::vector<uint32_t> o(n * times.size(), 7), p(n * times.size(), 7);
        std::vector<float> d(n * times.size(), 7.0f);
        for (size_t first = 0; first < times.size(); first += batch) {
          std::vector<BatchFrame> frames;
          for (size_t f = first; f < std::min(times.size(), first + batch); ++f)
            frames.push_back({.t = times[f],
                              .object = std::span(o).subspan(f * n, n),
                              .prim = std::span(p).subspan(f * n, n),
                              .depth = std::span(d).subspan(f * n, n)});
          grid.advance_and_read_out(frames);
          EXPECT_EQ(grid.now(), frames.back().t);
          for (size_t k = 0; k < frames.size(); ++k) {
            const size_t f = first + k;
            const std::string where = std::string(depth_sort_name(sort)) + ", " +
                                      std::to_string(threads) + " threads, batches of " +
                                      std::to_string(batch) + ", t " + std::to_string(times[f]);
            EXPECT_EQ(frames[k].events, events[f]) << where;
            EXPECT_GE(frames[k].events_s, 0.0);
            EXPECT_GE(frames[k].readout_s, 0.0);
            EXPECT_TRUE(std::equal(object[f].begin(), object[f].end(), o.begin() + f * n)) << where;
            EXPECT_TRUE(std::equal(prim[f].begin(), prim[f].end(), p.begin() + f * n)) << where;
            EXPECT_EQ(std::memcmp(depth[f].data(), d.data() + f * n, n * sizeof(float)), 0)
                << where;
          }
        }
        EXPECT_EQ(grid.event_count(), reference.event_count());
        EXPECT_GT(grid.timings().events + grid.timings().readout, 0.0);
      }
    }
}

TEST(GridReadout, BatchesRejectTimeGoingBackAndWrongBuffers) {
  const TestScene scene = readout_scene();
  const GridInput in = scene.input();
  FrustumGrid grid(in, 0.5);
  const size_t n = in.rays.pixel_count();
  std::vector<uint32_t> object(n), prim(n);
  std::vector<float> depth(n);
  std::vector<BatchFrame> back = {{.t = 0.25, .object = object, .prim = prim, .depth = depth}};
  EXPECT_THROW(grid.advance_and_read_out(back), std::invalid_argument);
  std::vector<BatchFrame> short_buffers = {
      {.t = 0.75, .object = std::span(object).first(n - 1), .prim = prim, .depth = depth}};
  EXPECT_THROW(grid.advance_and_read_out(short_buffers), std::invalid_argument);
  EXPECT_EQ(grid.now(), 0.5);  // nothing was advanced
}

}  // namespace
}  // namespace kinray
