// Coincident surfaces under the shutter: the pixels where two triangles lie in one place are ties
// of blurred frames, and nothing else is.
#include <gtest/gtest.h>

#include <numeric>

#include "tests/renderer/analytic_scenes.h"
#include "verification/coincident_fronts.h"
#include "verification/image_diff.h"

namespace kinray {
namespace {

using test::on_ray;

constexpr int kSize = 32;
const ShutterWindow kWindow{0.25, 0.5, 0.75};

// The plane z = 5 + 0.1 x, tilted so that its depths are not round numbers.
Vec3 on_plane(double x, double y, double shift = 0) {
  return {x + shift, y, 5 + 0.1 * (x + shift)};
}

// Triangle A covers the image's left half and a little more, triangle B its right half and a
// little more (they overlap in the columns around the centre), both in the plane above (B `gap`
// deeper along z), both sliding along the plane by 0.5 over the shot.
Object overlapping_panel(double gap) {
  std::vector<std::vector<Vec3>> keys;
  for (double shift : {0.0, 0.5}) {
    const Vec3 deeper(0, 0, gap);
    keys.push_back({on_plane(-30, -30, shift), on_plane(2, -30, shift), on_plane(2, 30, shift),
                    on_plane(-2, -30, shift) + deeper, on_plane(30, -30, shift) + deeper,
                    on_plane(-2, 30, shift) + deeper});
  }
  return test::camera_space_object("panel", {{0, 1, 2}, {3, 4, 5}}, keys, {0.0, 1.0});
}

Object wall() {
  return test::camera_space_object(
      "wall", {{0, 1, 2}},
      {{on_ray(-kSize, -kSize, 50, kSize, kSize), on_ray(3 * kSize, -kSize, 50, kSize, kSize),
        on_ray(-kSize, 3 * kSize, 50, kSize, kSize)}});
}

std::vector<size_t> every_pixel() {
  std::vector<size_t> pixels(size_t(kSize) * kSize);
  std::iota(pixels.begin(), pixels.end(), size_t(0));
  return pixels;
}

size_t at(int i, int j) {
  return size_t(j) * kSize + size_t(i);
}

TEST(CoincidentFronts, PixelsWhereTwoTrianglesOverlapInOnePlaneAreTies) {
  const Scene scene = test::analytic_scene({wall(), overlapping_panel(0)});
  const CameraSpaceScene cs = CameraSpaceScene::build(scene);
  const std::vector<uint8_t> ties = coincident_fronts(cs, kWindow, kSize, kSize, every_pixel());
  // Near the image's centre both triangles cover the ray robustly at every instant.
  EXPECT_EQ(ties[at(16, 16)], 1);
  EXPECT_EQ(ties[at(15, 18)], 1);
  // At the left edge only A covers it, at the top corners neither, behind them the wall.
  EXPECT_EQ(ties[at(1, 16)], 0);
  EXPECT_EQ(ties[at(0, 0)], 0);
  const size_t count = size_t(std::count(ties.begin(), ties.end(), uint8_t(1)));
  EXPECT_GT(count, 50u);
  EXPECT_LT(count, size_t(kSize) * kSize / 2);
}

TEST(CoincidentFronts, OverlappingSliversNarrowerThanTheEdgeToleranceAreTies) {
  // Seen from afar, BART's car panels are fans of slivers whose every edge passes within the
  // edge tolerance of the ray: two of them overlap around the centre ray of pixel (16, 16), in a
  // plane at depth 5, each about 4e-5 across (margins about 5e-6).
  const Vec3 c = 5 * Vec3(1.0 / 32, -1.0 / 32, 1.0);
  const double a = 2e-5;
  const std::vector<Vec3> slivers = {c + Vec3(-2 * a, -a, 0), c + Vec3(a, -a, 0),
                                     c + Vec3(a, 2 * a, 0),   c + Vec3(-a, -2 * a, 0),
                                     c + Vec3(2 * a, a, 0),   c + Vec3(-a, a, 0)};
  const Scene scene = test::analytic_scene(
      {wall(), test::camera_space_object("slivers", {{0, 1, 2}, {3, 4, 5}}, {slivers})});
  const CameraSpaceScene cs = CameraSpaceScene::build(scene);
  const std::vector<uint8_t> ties = coincident_fronts(cs, kWindow, kSize, kSize, every_pixel());
  EXPECT_EQ(ties[at(16, 16)], 1);
  EXPECT_EQ(std::count(ties.begin(), ties.end(), uint8_t(1)), 1);
}

TEST(CoincidentFronts, ParallelSurfacesApartByMoreThanRoundingAreNotTies) {
  // 1e-4 of the depth apart: every renderer resolves which is in front.
  const Scene scene = test::analytic_scene({wall(), overlapping_panel(5e-4)});
  const CameraSpaceScene cs = CameraSpaceScene::build(scene);
  const std::vector<uint8_t> ties = coincident_fronts(cs, kWindow, kSize, kSize, every_pixel());
  EXPECT_EQ(std::count(ties.begin(), ties.end(), uint8_t(1)), 0);
}

TEST(CoincidentFronts, TheSharedEdgeOfAMeshIsNotATie) {
  // Two triangles of one surface meet along an edge through the centre ray of pixel (10, 10):
  // both are hit there at one depth, but a shared edge is the surface, not two of them.
  const Vec3 ray(-11.0 / 32, 11.0 / 32, 1.0);
  const Vec3 p = 3 * ray + Vec3(0, 0.5, 0), q = 3 * ray - Vec3(0, 0.5, 0);
  const Vec3 l = 3 * ray + Vec3(-0.5, 0, 0), r = 3 * ray + Vec3(0.5, 0, 0);
  const Scene scene = test::analytic_scene(
      {wall(), test::camera_space_object("pair", {{0, 1, 2}, {1, 0, 3}}, {{p, q, l, r}})});
  CameraSpaceScene cs = CameraSpaceScene::build(scene);
  cs.objects[1].positions = {p, q, l, r};  // exactly (the fov folding is an ulp off 1)
  const std::vector<uint8_t> ties = coincident_fronts(cs, kWindow, kSize, kSize, every_pixel());
  EXPECT_EQ(std::count(ties.begin(), ties.end(), uint8_t(1)), 0);
}

TEST(CoincidentFronts, OnlyPixelsThatDifferFromTheReferenceAreChecked) {
  const Scene scene = test::analytic_scene({wall(), overlapping_panel(0)});
  const CameraSpaceScene cs = CameraSpaceScene::build(scene);
  Frame tested, reference;
  tested.resize(kSize, kSize);
  reference.resize(kSize, kSize);
  // The centre pixel differs by far more than the candidates' threshold, (15, 18) by less, and
  // the left-edge pixel (no tie there) by as much as the centre.
  tested.color[at(16, 16)] = Color(0.5f, 0.5f, 0.5f);
  tested.color[at(15, 18)] = Color::Constant(float(kCoincidenceCandidateError / 2));
  tested.color[at(1, 16)] = Color(0.5f, 0.5f, 0.5f);
  const std::vector<uint8_t> ties = coincident_fronts(cs, kWindow, tested, reference);
  EXPECT_EQ(ties[at(16, 16)], 1);
  EXPECT_EQ(ties[at(15, 18)], 0);
  EXPECT_EQ(ties[at(1, 16)], 0);
  // The colour error sets the tie aside and keeps the rest.
  const ColorError all = compare_colors(tested, reference);
  const ColorError aside = compare_colors(tested, reference, &ties);
  EXPECT_FLOAT_EQ(float(all.max_error), 0.5f);
  EXPECT_FLOAT_EQ(float(aside.max_error), 0.5f);  // the left-edge pixel
  EXPECT_LT(aside.mse, all.mse);
}

}  // namespace
}  // namespace kinray
