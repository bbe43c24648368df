// The hard instants of kinetic ray tracing, each built in code, rendered by the kinetic backend
// with its audit on and compared frame by frame with Embree (zero real mismatches; near a vertex at
// the eye, where Embree is no reference, with the brute-force sign rule) at frame times that hit
// the instant exactly: coplanar overlapping triangles, edges exactly through pixel centres, a depth
// swap exactly at a frame time, a vertex exactly on a row plane at a keyframe, objects inserted and
// removed mid-shot, geometry passing behind the camera and through the eye, and zero-area
// triangles. Where the mathematics gives the answer (who is in front just after a swap, what a ray
// on a shared edge must see, that a degenerate or edge-on triangle covers nothing), the test
// checks it.
//
// Positions are camera-space values set exactly after CameraSpaceScene::build (the analytic
// camera's fov scale is 1 only up to an ulp), dyadic wherever exactness matters, so "exactly"
// means exactly: an edge through the pixel centres of column c has E(d) == 0.0 for every ray of
// that column. The 32x32 image has dyadic pixel centres too.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <csignal>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <unistd.h>
#include <nlohmann/json.hpp>

#include "renderer/backends/backend.h"
#include "tests/renderer/analytic_scenes.h"
#include "verification/image_diff.h"

namespace kinray {
namespace {

constexpr int kSize = 32;  // pixel centres (2i + 1) / 32 - 1 are dyadic: exact in float and double

/// x / z of the centre of column i, y / z of the centre of row j.
double cx(int i) { return (2.0 * i + 1) / kSize - 1; }
double cy(int j) { return 1 - (2.0 * j + 1) / kSize; }
/// The camera-space point at image position (u, v) = (x / z, y / z) and depth z.
Vec3 at(double u, double v, double z) { return {u * z, v * z, z}; }
/// The pixel that contains image position (u, v).
std::pair<int, int> pixel_at(double u, double v) {
  return {int((u + 1) * kSize / 2), int((1 - v) * kSize / 2)};
}

/// One object of a hard-case scene, in exact camera-space positions.
struct Piece {
  std::string name;
  std::vector<Triangle> triangles;
  std::vector<std::vector<Vec3>> keys;  ///< [key][vertex]
  std::vector<double> times = {0.0};
  double appear = -kInfinity, disappear = kInfinity;
};

/// A wall at depth 4 behind everything, covering the whole view: what shows through a hole. Its
/// diagonal has slope 9/8 in the image, so unlike a square's it meets no pixel centre.
Piece wall() {
  return {"wall", {{0, 1, 2}, {0, 2, 3}}, {{at(-2, -2, 4), at(2.5, -2, 4), at(2, 2.5, 4), at(-2.5, 2, 4)}}};
}

/// A square of image half-size h centred at (u, v), at depth z (two triangles).
std::vector<Vec3> square(double u, double v, double h, double z) {
  return {at(u - h, v - h, z), at(u + h, v - h, z), at(u + h, v + h, z), at(u - h, v + h, z)};
}
const std::vector<Triangle> kSquare = {{0, 1, 2}, {0, 2, 3}};

/// The scene of some pieces, with the camera-space positions set exactly.
class ExactScene {
 public:
  explicit ExactScene(const std::vector<Piece>& pieces) {
    std::vector<Object> objects;
    for (const Piece& p : pieces) {
      Object o = test::camera_space_object(p.name, p.triangles, p.keys, p.times);
      o.appear = p.appear;
      o.disappear = p.disappear;
      objects.push_back(std::move(o));
    }
    m_scene = test::analytic_scene(std::move(objects));
    m_cs = CameraSpaceScene::build(m_scene);
    for (size_t o = 0; o < pieces.size(); ++o) {
      CameraSpaceObject& object = m_cs.objects[o];
      if (object.key_times != pieces[o].times) throw std::logic_error("keys must start at the camera's key, t = 0");
      for (size_t k = 0; k < pieces[o].keys.size(); ++k)
        for (size_t v = 0; v < object.vertex_count; ++v) object.positions[k * object.vertex_count + v] = pieces[o].keys[k][v];
    }
  }
  ExactScene(const ExactScene&) = delete;
  ExactScene& operator=(const ExactScene&) = delete;
  [[nodiscard]] const CameraSpaceScene& cs() const { return m_cs; }

 private:
  Scene m_scene;
  CameraSpaceScene m_cs;
};

struct Renders {
  std::vector<double> times;
  std::vector<Frame> kinetic, embree, exact;
  nlohmann::json stats;
  std::string error;  ///< why nothing was rendered: the child crashed, hung or threw
};

BackendConfig hard_case_config() {
  BackendConfig config;
  config.width = config.height = kSize;
  config.threads = 2;
  config.audit = true;
  return config;
}

void render_frames(const CameraSpaceScene& cs, Renders& r) {
  auto kinetic = make_backend("kinetic", cs, hard_case_config());
  auto embree = make_backend("embree", cs, hard_case_config());
  for (double t : r.times) {
    r.kinetic.emplace_back();
    r.embree.emplace_back();
    kinetic->render(t, r.kinetic.back());
    embree->render(t, r.embree.back());
    r.exact.push_back(test::exact_frame(cs, kSize, kSize, t));
  }
  kinetic->write_stats(r.stats);
}

extern "C" void on_alarm(int) {
  const char message[] = "HANG: the hard case did not finish rendering within 60 s\n";
  (void)!write(2, message, sizeof message - 1);
  _exit(3);
}

/// Renders `times` with the kinetic backend (audit on), Embree and the brute-force sign rule --
/// first in a child process (a GoogleTest death test, re-executed because Embree's threads do
/// not survive a fork), so that a crash (an audit KINRAY_CHECK aborts), an exception or a hang
/// (60 s) fails this test, with the child's message, without taking the test binary down; then,
/// when the child finished, here.
Renders render(const CameraSpaceScene& cs, const std::vector<double>& times) {
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  const ::testing::TestResult* result = ::testing::UnitTest::GetInstance()->current_test_info()->result();
  const int parts = result->total_part_count();
  EXPECT_EXIT(
      {
        std::signal(SIGALRM, on_alarm);
        alarm(60);
        Renders child;
        child.times = times;
        try {
          render_frames(cs, child);
        } catch (const std::exception& e) {
          std::fprintf(stderr, "the kinetic backend threw: %s\n", e.what());
          std::_Exit(2);
        }
        std::_Exit(0);
      },
      ::testing::ExitedWithCode(0), "")
      << "rendering crashed, threw or hung (the child's output is above)";
  Renders r;
  r.times = times;
  if (result->total_part_count() != parts) {
    r.error = "rendering failed in the child process";
    return r;
  }
  try {
    render_frames(cs, r);
  } catch (const std::exception& e) {
    r.error = e.what();
  }
  return r;
}

/// The first real mismatch of a diff, as "pixel (i, j): kinetic o/p, other o/p".
std::string first_real(const FrameDiff& diff, const Frame& a, const Frame& b) {
  for (int j = 0; j < diff.height; ++j)
    for (int i = 0; i < diff.width; ++i) {
      const size_t p = a.index(i, j);
      if (diff.pixels[p] != PixelClass::kReal) continue;
      std::ostringstream text;
      auto id = [](const Frame& f, size_t q) {
        return f.object[q] == kNoHit ? std::string("background")
                                     : std::to_string(f.object[q]) + "/" + std::to_string(f.prim[q]);
      };
      text << "first at pixel (" << i << ", " << j << "): kinetic " << id(a, p) << ", other " << id(b, p);
      return text.str();
    }
  return "";
}

/// Zero real mismatches against Embree in every frame, except at `sign_rule_times`, where
/// Embree is no reference (a ray that starts on a triangle) and the brute-force sign rule is used.
/// (The sign rule is not used elsewhere: a ray exactly on a shared edge pierces neither triangle
/// by the strict rule, a hole that FrameComparator rightly calls a crack.)
void expect_agreement(const CameraSpaceScene& cs, const Renders& r, const std::vector<double>& sign_rule_times = {}) {
  ASSERT_EQ(r.error, "") << "the kinetic backend failed";
  ASSERT_EQ(r.kinetic.size(), r.times.size());
  FrameComparator comparator(cs);
  for (size_t f = 0; f < r.times.size(); ++f) {
    const bool sign_rule = std::find(sign_rule_times.begin(), sign_rule_times.end(), r.times[f]) != sign_rule_times.end();
    const Frame& reference = sign_rule ? r.exact[f] : r.embree[f];
    const FrameDiff diff = comparator.compare(r.kinetic[f], reference);
    EXPECT_EQ(diff.mismatch_real, 0u) << "against " << (sign_rule ? "the sign rule" : "Embree") << " at t = "
                                      << r.times[f] << ", " << first_real(diff, r.kinetic[f], reference);
  }
}

/// Number of pixels of frame `f` that show `object`.
size_t pixels_of(const Frame& f, uint32_t object) {
  return size_t(std::count(f.object.begin(), f.object.end(), object));
}

TEST(HardCases, CoplanarOverlappingTriangles) {
  // Objects 1 and 2 overlap in the plane z = 2; object 1 also holds a duplicate of its triangle
  // with the opposite winding; object 3 slides across both in the same plane.
  const ExactScene s({wall(),
                      {"a", {{0, 1, 2}, {0, 2, 1}}, {{at(-0.75, -0.75, 2), at(0.5, -0.75, 2), at(-0.75, 0.5, 2)}}},
                      {"b", {{0, 1, 2}}, {{at(0.75, 0.75, 2), at(-0.5, 0.75, 2), at(0.75, -0.5, 2)}}},
                      {"c", kSquare, {square(-0.5, 0, 0.25, 2), square(0.5, 0, 0.25, 2)}, {0, 1}}});
  const std::vector<double> times = {0, 0.25, 0.5, 0.75, 1};
  const Renders r = render(s.cs(), times);
  expect_agreement(s.cs(), r);
  if (r.kinetic.size() != times.size()) return;
  for (size_t f = 0; f < times.size(); ++f) {
    SCOPED_TRACE("t = " + std::to_string(times[f]));
    const Frame& k = r.kinetic[f];
    // Where a and b overlap (and c is elsewhere), the ray sees a or b at depth 2, never the wall.
    const auto [i, j] = pixel_at(0.0 + 1.0 / 64, 0.25 + 1.0 / 64);
    const size_t p = k.index(i, j);
    EXPECT_TRUE(k.object[p] == 1 || k.object[p] == 2 || k.object[p] == 3) << k.object[p];
    EXPECT_NEAR(k.depth[p], 2.0, 1e-6);
    // Every pixel that the sign rule sees at depth 2 is seen at depth 2.
    for (size_t q = 0; q < k.pixel_count(); ++q)
      if (r.exact[f].object[q] != kNoHit && r.exact[f].depth[q] < 3) {
        EXPECT_NEAR(k.depth[q], 2.0, 1e-6) << q;
      }
  }
}

/// Two triangles (p, q, l) and (q, p, r) sharing the edge p q, wound so that det(v0, v1, v2) has
/// the sign `orientation` (+1: counter-clockwise in the image, -1: clockwise).
Piece diamond(const std::vector<Vec3>& pqlr, int orientation) {
  std::vector<Triangle> triangles = {{0, 1, 2}, {1, 0, 3}};
  if ((pqlr[0].dot(pqlr[1].cross(pqlr[2])) > 0) != (orientation > 0)) triangles = {{1, 0, 2}, {0, 1, 3}};
  return {"diamond", triangles, {pqlr}};
}

/// A diamond at depth 2 whose shared edge lies exactly in the plane of the centre rays of
/// `column`, over image heights v0 +- 1/4, moved sideways by du (camera units).
Piece diamond_on_column(int column, double v0, int orientation, double du = 0) {
  const double x = cx(column) * 2 + du;
  return diamond({{x, (v0 + 0.25) * 2, 2}, {x, (v0 - 0.25) * 2, 2}, {x - 0.5, v0 * 2, 2}, {x + 0.5, v0 * 2, 2}},
                 orientation);
}

/// A diamond at depth 2 whose shared edge lies exactly in the plane of the centre rays of `row`.
Piece diamond_on_row(int row, double u0, int orientation) {
  const double y = cy(row) * 2;
  return diamond({{(u0 - 0.25) * 2, y, 2}, {(u0 + 0.25) * 2, y, 2}, {u0 * 2, y + 0.5, 2}, {u0 * 2, y - 0.5, 2}},
                 orientation);
}

/// The centre rays of `column` between image heights v_low and v_high (exclusive) all lie on the
/// shared edge: each must see the diamond (object `object`), which is closed across that edge.
void expect_closed_column(const Frame& k, uint32_t object, int column, double v_low, double v_high) {
  for (int j = 0; j < kSize; ++j) {
    if (!(cy(j) > v_low && cy(j) < v_high)) continue;
    EXPECT_EQ(k.object[k.index(column, j)], object) << "t = " << k.time << ": the ray of pixel (" << column << ", " << j
                                                     << ") lies on the shared edge; it saw through the mesh";
  }
}

void expect_closed_row(const Frame& k, uint32_t object, int row, double u_low, double u_high) {
  for (int i = 0; i < kSize; ++i) {
    if (!(cx(i) > u_low && cx(i) < u_high)) continue;
    EXPECT_EQ(k.object[k.index(i, row)], object) << "t = " << k.time << ": the ray of pixel (" << i << ", " << row
                                                  << ") lies on the shared edge; it saw through the mesh";
  }
}

// Two diamonds wound `winding` (+1: counter-clockwise in the image) whose shared edges lie on
// the centre rays of column 8 and row 24: agreement with Embree, and no crack along either edge.
void expect_diamonds_closed_along_their_shared_edges(int winding) {
  const ExactScene s({wall(), diamond_on_column(8, 0.5, winding), diamond_on_row(24, 0.5, winding)});
  const Renders r = render(s.cs(), {0, 1});
  expect_agreement(s.cs(), r);
  for (const Frame& k : r.kinetic) {
    expect_closed_column(k, 1, 8, 0.25, 0.75);
    expect_closed_row(k, 2, 24, 0.25, 0.75);
  }
}

TEST(HardCases, SharedEdgeExactlyThroughPixelCentresCounterClockwise) {
  // The edge functions of the shared edges vanish exactly on those rays.
  const Vec3 p(cx(8) * 2, 1.5, 2), q(cx(8) * 2, 0.5, 2);
  for (int j = 0; j < kSize; ++j) ASSERT_EQ(p.cross(q).dot(Vec3(cx(8), cy(j), 1)), 0.0);
  expect_diamonds_closed_along_their_shared_edges(+1);
}

// The same edges wound clockwise in the image (det < 0). The edge function of a ray on the edge
// vanishes identically while the edge stands still; a symbolic perturbation that read it as
// positive in both triangles left the wall showing through along the whole edge (column 8, rows
// 4..11; row 24, columns 20..27). The perturbation of the ray, d + (eps, eps^2, 0), gives the two
// triangles opposite signs there, so exactly one of them covers each such ray, for both windings.
TEST(HardCases, SharedEdgeExactlyThroughPixelCentresClockwise) {
  expect_diamonds_closed_along_their_shared_edges(-1);
}

TEST(HardCases, SharedEdgeReachesPixelCentresAtAFrameTime) {
  // Two diamonds (one of each winding) and a single triangle slide sideways by 3/4 pixel each
  // way; at t = 0.5 exactly their edges lie on the centre rays of columns 8 and 24 (shared
  // edges) and 14 (a silhouette edge). Moving through the rays, the edge functions change sign
  // there, and the sign just after decides: both windings must stay closed.
  const double shift = 3.0 / 32;  // camera units at depth 2: 3/4 of a pixel
  auto moving = [&](int column, int orientation) {
    Piece a = diamond_on_column(column, 0.5, orientation, -shift);
    a.keys.push_back(diamond_on_column(column, 0.5, orientation, shift).keys[0]);
    a.times = {0, 1};
    return a;
  };
  auto silhouette_at = [](double du) {
    const double x = cx(14) * 2 + du;
    return std::vector<Vec3>{{x, -0.5, 2}, {x, -1.5, 2}, {x - 0.5, -1, 2}};
  };
  const Piece silhouette{"silhouette", {{0, 1, 2}}, {silhouette_at(-shift), silhouette_at(shift)}, {0, 1}};
  const ExactScene s({wall(), moving(8, +1), moving(24, -1), silhouette});
  const std::vector<double> times = {0, 0.25, 0.5, 0.75, 1};
  const Renders r = render(s.cs(), times);
  expect_agreement(s.cs(), r);
  ASSERT_EQ(r.kinetic.size(), times.size());
  expect_closed_column(r.kinetic[2], 1, 8, 0.25, 0.75);
  expect_closed_column(r.kinetic[2], 2, 24, 0.25, 0.75);
}

TEST(HardCases, DepthSwapExactlyAtAFrameTime) {
  // a: a square at depth 2. b: a smaller square moving away along its own rays, z = 1.5 + t, so its
  // image never changes and it passes a at t = 0.5 exactly, over its whole area. docs/design.md:
  // events at t <= t_f are processed before the read-out, and a root is decided by the sign just
  // after it, so at t = 0.5 a is already in front.
  auto along_rays = [](double z) { return square(0, 0, 0.375, z); };
  const ExactScene s({wall(), {"a", kSquare, {square(0, 0, 0.75, 2)}},
                      {"b", kSquare, {along_rays(1.5), along_rays(2.5)}, {0, 1}}});
  const double eps = std::ldexp(1.0, -20);
  const std::vector<double> times = {0, 0.25, 0.5 - eps, 0.5, 0.5 + eps, 0.75, 1};
  const Renders r = render(s.cs(), times);
  expect_agreement(s.cs(), r);
  ASSERT_EQ(r.kinetic.size(), times.size());
  const auto [i, j] = pixel_at(0.125 + 1.0 / 64, 0.125 + 1.0 / 64);
  const size_t p = r.kinetic[0].index(i, j);
  const std::vector<uint32_t> front = {2, 2, 2, 1, 1, 1, 1};  // b before the swap, a from t = 0.5 on
  for (size_t f = 0; f < times.size(); ++f) {
    EXPECT_EQ(r.kinetic[f].object[p], front[f]) << "t = 0.5 + " << (times[f] - 0.5);
    if (std::abs(times[f] - 0.5) > 0.1) {
      EXPECT_EQ(r.embree[f].object[p], front[f]) << "t = " << times[f];
    }
  }
  EXPECT_EQ(r.kinetic[3].depth[p], 2.0f);
  // The whole inside of b swaps at once: every pixel that showed b just before shows a at 0.5.
  EXPECT_EQ(pixels_of(r.kinetic[3], 2), 0u);
  EXPECT_EQ(pixels_of(r.kinetic[2], 2), pixels_of(r.embree[2], 2));
  EXPECT_GT(r.stats["events"]["swap"].get<uint64_t>(), 0u);
}

TEST(HardCases, TiltedDepthSwapCrossesRowsAtFrameTimes) {
  // b lies in the plane z = 1.5 + t + y / 4, a at z = 2: along the centre rays of row j they are
  // at the same depth exactly at t_j = (2j + 1) / 64, when the crossing line passes the row.
  // Just before t_j b is in front on row j, just after a.
  auto tilted = [](double t) {
    std::vector<Vec3> corners;
    for (const auto& [x, y] : {std::pair{-0.75, -0.75}, {0.75, -0.75}, {0.75, 0.75}, {-0.75, 0.75}})
      corners.emplace_back(x, y, 1.5 + t + y / 4);
    return corners;
  };
  const ExactScene s({wall(), {"a", kSquare, {square(0, 0, 0.5, 2)}}, {"b", kSquare, {tilted(0), tilted(1)}, {0, 1}}});
  const int row = 12;
  const double t_row = (2.0 * row + 1) / 64, eps = std::ldexp(1.0, -16);
  // 17/64 is the swap of row 8.
  const std::vector<double> times = {0, 17.0 / 64, t_row - eps, t_row, t_row + eps, 0.5, 1};
  const Renders r = render(s.cs(), times);
  expect_agreement(s.cs(), r);
  ASSERT_EQ(r.kinetic.size(), times.size());
  const int column = 15;
  const size_t p = r.kinetic[0].index(column, row);
  EXPECT_EQ(r.kinetic[2].object[p], 2u) << "just before the swap of row " << row;
  EXPECT_EQ(r.kinetic[4].object[p], 1u) << "just after the swap of row " << row;
  // At the instant both are at depth 2 along the ray: whichever is shown, at depth 2.
  EXPECT_NEAR(r.kinetic[3].depth[p], 2.0, 1e-9);
  // Rows above the crossing line (nearer the top) already show a, rows below still show b.
  EXPECT_EQ(r.kinetic[3].object[r.kinetic[3].index(column, row - 2)], 1u);
  EXPECT_EQ(r.kinetic[3].object[r.kinetic[3].index(column, row + 2)], 2u);
}

TEST(HardCases, VertexExactlyOnARowPlaneAtAKeyframe) {
  // Row 12's centre rays span the plane y = z * 7 / 32. Each triangle has one vertex that, at the
  // keyframe t = 0.5, lies exactly on that plane: it crosses it (changing speed at the key), it
  // touches it and turns back, or it slides inside it for the whole first segment.
  const double y = cy(12) * 2;  // the row plane at depth 2
  auto triangle = [&](double u, const std::vector<Vec3>& apex) {
    Piece p{"t", {{0, 1, 2}}, {}, {0, 0.5, 1}};
    for (const Vec3& a : apex) p.keys.push_back({at(u - 0.25, -0.5, 2), at(u + 0.25, -0.5, 2), a});
    return p;
  };
  const ExactScene s({wall(),
                      triangle(-0.6, {{-1.2, y + 0.5, 2}, {-1.2, y, 2}, {-1.0, y - 1, 2}}),       // crosses
                      triangle(0.0, {{0.0, y + 0.5, 2}, {0.0, y, 2}, {0.0, y + 0.25, 2}}),        // touches
                      triangle(0.6, {{1.2, y, 2}, {1.0, cy(12) * 3, 3}, {1.2, y - 0.5, 2}})});  // slides
  const std::vector<double> times = {0, 0.25, 0.5, 0.75, 1};
  const Renders r = render(s.cs(), times);
  expect_agreement(s.cs(), r);
  EXPECT_GT(r.stats["events"]["vertex_row"].get<uint64_t>(), 0u);
  EXPECT_GT(r.stats["events"]["flightplan"].get<uint64_t>(), 0u);
}

// Found by tools/diff_all.sh on ASE/RotatingCube.ASE, 3DS/RotatingCube.3DS, ASE/anim.ASE and
// LWS/move_xz_*.lws, move_y_pre_ofrep_post_osc.lws (fixed by d738b5c). The edge v0 v1 is parallel
// to the image rows -- its two vertices share their camera-space y and z, as the edges of a box
// parallel to the camera's x axis do -- so both vertices cross each row plane at the same instant.
// The triangle is tilted (v2 nearer). The edge sweeps up across row 8 (y / z = 15/32) at
// t = 9/16; from then on row 8 must be covered between the edges v2 v0 and v2 v1.
TEST(HardCases, EdgeParallelToTheRowsSweepsAcrossARowPlane) {
  auto key = [](double v) { return std::vector<Vec3>{at(-0.5, v, 3), at(0.5, v, 3), at(0.1, -0.5, 2)}; };
  const ExactScene s({{"t", {{0, 1, 2}}, {key(0.3), key(0.6)}, {0, 1}}});
  const std::vector<double> times = {0, 0.5, 0.5625, 0.625, 0.75, 1};
  const Renders r = render(s.cs(), times);
  // At t = 9/16 the edge, a silhouette with nothing behind it, lies exactly on the centres of
  // row 8: Embree's closed triangles cover them, the kinetic backend's perturbation of the ray
  // (docs/kinetic_grid.md) and the strict sign rule do not. Hit against background is never a
  // tie (a tie needs both sides to hit something), so the sign rule is the reference there.
  expect_agreement(s.cs(), r, {0.5625});
  ASSERT_EQ(r.kinetic.size(), times.size());
  // Just after the crossing, row 8 holds the triangle in the middle of the image.
  EXPECT_EQ(r.kinetic[3].object[r.kinetic[3].index(16, 8)], 0u) << "row 8 is covered after t = 9/16";
}

TEST(HardCases, ObjectsInsertedAndRemovedMidShot) {
  // Visible on [appear, disappear): x from 0.25 to 0.75; y appears at its keyframe 0.25 while
  // moving; z lives between two frames and is never seen; w leaves exactly at the last frame.
  Piece x{"x", kSquare, {square(-0.5, 0.5, 0.25, 2)}};
  x.appear = 0.25;
  x.disappear = 0.75;
  Piece y{"y", kSquare, {square(0.5, 0.5, 0.25, 2), square(0.5, 0.5, 0.25, 2), square(0.5, -0.25, 0.25, 3)}, {0, 0.25, 1}};
  y.appear = 0.25;
  Piece z{"z", kSquare, {square(0, 0, 0.5, 1)}};  // in front of everything, over the whole centre
  z.appear = 0.55;
  z.disappear = 0.6;
  Piece w{"w", kSquare, {square(-0.5, -0.5, 0.25, 2)}};
  w.disappear = 1;
  const ExactScene s({wall(), x, y, z, w});
  const std::vector<double> times = {0, 0.25, 0.5, 0.75, 1};
  const Renders r = render(s.cs(), times);
  expect_agreement(s.cs(), r);
  ASSERT_EQ(r.kinetic.size(), times.size());
  const auto [xi, xj] = pixel_at(-0.5 + 1.0 / 64, 0.5 + 1.0 / 64);
  const auto [wi, wj] = pixel_at(-0.5 + 1.0 / 64, -0.5 + 1.0 / 64);
  for (size_t f = 0; f < times.size(); ++f) {
    const double t = times[f];
    const Frame& k = r.kinetic[f];
    EXPECT_EQ(k.object[k.index(xi, xj)], t >= 0.25 && t < 0.75 ? 1u : 0u) << "t = " << t;
    EXPECT_EQ(pixels_of(k, 2) > 0, t >= 0.25) << "t = " << t;
    EXPECT_EQ(pixels_of(k, 3), 0u) << "t = " << t;
    EXPECT_EQ(k.object[k.index(wi, wj)], t < 1 ? 4u : 0u) << "t = " << t;
  }
  EXPECT_GT(r.stats["events"]["insert"].get<uint64_t>(), 0u);
  EXPECT_GT(r.stats["events"]["delete"].get<uint64_t>(), 0u);
}

TEST(HardCases, GeometryPassingBehindTheCamera) {
  // p: a triangle flying from depth 3 to depth -3, all three vertices on the eye plane at t = 0.5
  // (edge-on: it covers nothing then; the eye is outside it), behind the camera after. q: a floor
  // triangle that straddles the eye plane all shot long. r: one vertex crossing the eye plane at
  // t = 0.5 while the others stay in front. e: the eye in its plane at t = 0.5 (an orientation
  // event). Coordinates are generic: no edge meets a pixel centre.
  const Piece p{"p", {{0, 1, 2}},
                {{{0.3, -0.2, 3}, {1.1, -0.3, 3}, {0.6, 0.55, 3}}, {{0.3, -0.2, -3}, {1.1, -0.3, -3}, {0.6, 0.55, -3}}},
                {0, 1}};
  const Piece q{"q", {{0, 1, 2}}, {{{-1, -0.5, -1}, {1.05, -0.5, -1}, {0.1, -0.5, 3.1}}}};
  const Piece rr{"r", {{0, 1, 2}},
                 {{{0.3, 0.45, 1}, {1.45, 1.05, 2}, {0.95, 1.6, 2}}, {{0.3, 0.45, -1}, {1.45, 1.05, 2}, {0.95, 1.6, 2}}},
                 {0, 1}};
  const Piece e{"e", {{0, 1, 2}},
                {{{-1, 0.5, 1}, {-0.45, 0.5, 1.1}, {-0.7, 0.5, 3.1}}, {{-1, -0.5, 1}, {-0.45, -0.5, 1.1}, {-0.7, -0.5, 3.1}}},
                {0, 1}};
  const ExactScene s({wall(), p, q, rr, e});
  const std::vector<double> times = {0, 0.25, 0.4375, 0.5, 0.5625, 0.75, 1};
  const Renders r = render(s.cs(), times);
  expect_agreement(s.cs(), r);
  ASSERT_EQ(r.kinetic.size(), times.size());
  EXPECT_GT(pixels_of(r.kinetic[0], 1), 0u);
  EXPECT_EQ(pixels_of(r.kinetic[3], 1), 0u) << "edge-on at t = 0.5: p covers nothing";
  EXPECT_EQ(pixels_of(r.kinetic[3], 4), 0u) << "the eye is in e's plane at t = 0.5: e covers nothing";
  for (size_t f = 4; f < times.size(); ++f) EXPECT_EQ(pixels_of(r.kinetic[f], 1), 0u) << "p is behind the eye";
  for (const Frame& k : r.kinetic) EXPECT_GT(pixels_of(k, 2), 0u) << "q is always partly in front";
  EXPECT_GT(pixels_of(r.kinetic[5], 3), 0u) << "r still shows its part in front of the eye";
  EXPECT_GT(r.stats["events"]["orientation"].get<uint64_t>(), 0u);
}

// o's first vertex moves along its own ray, through the eye at t = 0.5 and behind it after. At
// t = 0.5 the eye is a vertex of o, so its plane holds the eye (det = 0) and by the sign rule it
// covers nothing, although the pixel orders hold the coverage of just after 0.5: the read-out must
// see that the front does not pierce the ray at that instant and show what is behind. Near the
// instant Embree is no reference: it forms o's edges v1 - v0 in float, where a vertex 1e-6 from
// the eye is lost to cancellation (6 to 140 real mismatches against the exact sign rule within
// 1e-6 of t = 0.5, and at t = 0.5 every ray starts on o and gets a hit at distance 0); those
// frames are compared with the brute-force sign rule in double.
TEST(HardCases, VertexPassingThroughTheEye) {
  const Piece o{"o", {{0, 1, 2}},
                {{{0.27, -0.52, 1}, {1.05, -1.45, 2}, {1.55, -0.95, 2}},
                 {{-0.27, 0.52, -1}, {1.05, -1.45, 2}, {1.55, -0.95, 2}}},
                {0, 1}};
  const ExactScene s({wall(), o});
  const double eps = std::ldexp(1.0, -20);
  const std::vector<double> times = {0, 0.25, 0.5 - eps, 0.5, 0.5 + eps, 0.75, 1};
  const Renders r = render(s.cs(), times);
  expect_agreement(s.cs(), r, {0.5 - eps, 0.5, 0.5 + eps});
  ASSERT_EQ(r.kinetic.size(), times.size());
  EXPECT_EQ(pixels_of(r.kinetic[3], 1), 0u) << "at t = 0.5 the eye is a vertex of o: o covers nothing";
  EXPECT_GT(pixels_of(r.kinetic[1], 1), 0u);
  EXPECT_GT(pixels_of(r.kinetic[5], 1), 0u) << "behind the eye, o straddles the eye plane and shows";
}

// The centre ray of pixel (24, 4) lies exactly on r's static edge a b (u + v = 1.25), and r's
// first vertex sweeps the plane of r through the eye at t = 0.1: there N_r and D_r (depth = N / D)
// vanish together and change sign, so N_r D_wall - N_wall D_r changes sign while r's depth along
// the ray stays finite. That root is no swap (the audit used to abort on "key values out of
// order", an ulp before the orientation event): pixel_depth_order.h divides it out.
TEST(HardCases, StaticEdgeOnPixelCentresWhileItsPlaneSweepsThroughTheEye) {
  const Piece rr{"r", {{0, 1, 2}},
                 {{{0.5, 0.5, 1}, at(0.75, 0.5, 2), at(0.5, 0.75, 2)}, {{0.5, 0.5, -1}, at(0.75, 0.5, 2), at(0.5, 0.75, 2)}},
                 {0, 1}};
  const ExactScene s({wall(), rr});
  ASSERT_EQ(at(0.75, 0.5, 2).cross(at(0.5, 0.75, 2)).dot(Vec3(cx(24), cy(4), 1)), 0.0);
  const Renders r = render(s.cs(), {0, 0.0625, 0.125, 0.25, 0.5, 1});
  expect_agreement(s.cs(), r);
}

TEST(HardCases, PixelsStayCoveredWhileThePlaneSweepsThroughTheEye) {
  // r's plane sweeps through the eye at t = 1/8: its first vertex slides in the image across the
  // line u + v = 5/4 while its other two cross it the other way, so at t = 1/8 the image of r is a
  // segment of that line and the centre rays of pixels (24, 4) .. (27, 7) lie in r's plane. O and
  // all three edge functions of those rays change sign together there, so the rays stay inside r
  // (at depth 1.8, in front of the wall) just before and just after, while D = (e1 x e2) . d
  // changes sign: the depth certificate against the wall has a root there that is no swap. At
  // t = 1/8 itself the plane holds the eye and r covers nothing: the wall shows there
  // (checked against the sign rule; Embree is no reference for a ray lying in a triangle's plane).
  const Piece rr{"r", {{0, 1, 2}},
                 {{{0.5, 0.5, 1}, at(25.0 / 32, 0.5, 2), at(17.0 / 32, 0.75, 2)},
                  {{1.5, 1.5, 1}, at(17.0 / 32, 0.5, 2), at(9.0 / 32, 0.75, 2)}},
                 {0, 1}};
  const ExactScene s({wall(), rr});
  const double eps = std::ldexp(1.0, -8);
  const std::vector<double> times = {0, 0.0625, 0.125 - eps, 0.125, 0.125 + eps, 0.25, 0.5};
  const Renders r = render(s.cs(), times);
  expect_agreement(s.cs(), r, {0.125});
  ASSERT_EQ(r.kinetic.size(), times.size());
  for (size_t f = 0; f < times.size(); ++f)
    for (int i = 24; i < 27; ++i) {
      const Frame& k = r.kinetic[f];
      const size_t p = k.index(i, i - 20);
      EXPECT_EQ(k.object[p], times[f] == 0.125 ? 0u : 1u) << "t = " << times[f] << ", pixel (" << i << ", " << i - 20 << ")";
      if (times[f] != 0.125) {
        EXPECT_NEAR(k.depth[p], 1.8, 1e-5) << "t = " << times[f];
      }
    }
  EXPECT_GT(r.stats["events"]["orientation"].get<uint64_t>(), 0u);
}

TEST(HardCases, DegenerateTriangles) {
  // Zero area for ever: two equal vertices, three collinear ones, a point, and a sliver inside a
  // quad whose diagonal it lies on. c collapses onto a line at t = 0.5 and flips its winding
  // (an orientation event); d touches a line at its keyframe t = 0.5 and opens again.
  const Piece still{"still",
                    {{0, 0, 1}, {2, 3, 4}, {5, 5, 5}},
                    {{at(-0.75, 0.75, 2), at(-0.5, 0.5, 2), at(-0.75, 0.25, 2), at(-0.5, 0.25, 2), at(-0.25, 0.25, 2),
                      at(-0.4, 0.6, 2)}}};
  const Piece quad{"quad", {{0, 1, 2}, {0, 4, 2}, {0, 2, 3}},
                   {{at(0.25, 0.25, 2), at(0.75, 0.25, 2), at(0.75, 0.75, 2), at(0.25, 0.75, 2), at(0.5, 0.5, 2)}}};
  const Piece c{"c", {{0, 1, 2}},
                {{at(-0.75, -0.75, 2), at(-0.25, -0.75, 2), at(-0.5, -0.25, 2)},
                 {at(-0.75, -0.75, 2), at(-0.25, -0.75, 2), at(-0.5, -1.25, 2)}},
                {0, 1}};
  const Piece d{"d", {{0, 1, 2}},
                {{at(0.25, -0.75, 2), at(0.75, -0.75, 2), at(0.5, -0.25, 2)},
                 {at(0.25, -0.75, 2), at(0.75, -0.75, 2), at(0.5, -0.75, 2)},
                 {at(0.25, -0.75, 2), at(0.75, -0.75, 2), at(0.5, -0.375, 2)}},
                {0, 0.5, 1}};
  const ExactScene s({wall(), still, quad, c, d});
  const std::vector<double> times = {0, 0.25, 0.5, 0.75, 1};
  const Renders r = render(s.cs(), times);
  expect_agreement(s.cs(), r);
  ASSERT_EQ(r.kinetic.size(), times.size());
  for (size_t f = 0; f < times.size(); ++f) {
    const Frame& k = r.kinetic[f];
    EXPECT_EQ(pixels_of(k, 1), 0u) << "zero-area triangles cover nothing, t = " << times[f];
    for (size_t q = 0; q < k.pixel_count(); ++q)
      if (k.object[q] == 2) {
        EXPECT_NE(k.prim[q], 1u) << "the sliver covers nothing";
      }
    EXPECT_GT(pixels_of(k, 2), 0u);
  }
  EXPECT_EQ(pixels_of(r.kinetic[2], 3), 0u) << "c is a segment at t = 0.5";
  EXPECT_EQ(pixels_of(r.kinetic[2], 4), 0u) << "d is a segment at t = 0.5";
  EXPECT_GT(pixels_of(r.kinetic[4], 3), 0u) << "c is open again, wound the other way";
  EXPECT_GT(pixels_of(r.kinetic[4], 4), 0u);
}

}  // namespace
}  // namespace kinray
