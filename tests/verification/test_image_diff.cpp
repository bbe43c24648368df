// The image diff: ties and real mismatches on frames whose geometry is known exactly.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <sstream>

#include "tests/renderer/analytic_scenes.h"
#include "util/input_error.h"
#include "verification/image_diff.h"

namespace kinray {
namespace {

using test::on_ray;

constexpr int kSize = 32;

// The centre ray of pixel (10, 10) of a 32 x 32 image is d = (-11/32, 11/32, 1): dyadic, so edge
// functions of points built from it below are computed exactly.
const Vec3 kRay(-11.0 / 32, 11.0 / 32, 1.0);
constexpr int kI = 10, kJ = 10;

// Camera-space positions are set exactly (CameraSpaceScene::build folds 1 / tan 45, an ulp off 1).
void set_positions(CameraSpaceScene& cs, size_t object, const std::vector<Vec3>& positions) {
  cs.objects[object].positions = positions;
}

// A wall at depth 10 covering the whole image.
Object wall() {
  return test::camera_space_object(
      "wall", {{0, 1, 2}},
      {{on_ray(-kSize, -kSize, 10, kSize, kSize), on_ray(3 * kSize, -kSize, 10, kSize, kSize),
        on_ray(-kSize, 3 * kSize, 10, kSize, kSize)}});
}

// Two triangles at depth ~3 sharing the edge p q, which passes exactly through the ray of pixel
// (10, 10): L = (p, q, l) lies left of it, R = (q, p, r) right.
struct SharedEdge {
  Vec3 p = 3 * kRay + Vec3(0, 0.5, 0), q = 3 * kRay - Vec3(0, 0.5, 0);
  Vec3 l = 3 * kRay + Vec3(-0.5, 0, 0), r = 3 * kRay + Vec3(0.5, 0, 0);
  Object object() const {
    return test::camera_space_object("pair", {{0, 1, 2}, {1, 0, 3}}, {{p, q, l, r}});
  }
  std::vector<Vec3> exact() const { return {p, q, l, r}; }
};

Frame background_frame(double t = 0) {
  Frame frame;
  frame.resize(kSize, kSize);
  frame.time = t;
  return frame;
}

void set_pixel(Frame& frame, int i, int j, uint32_t object, uint32_t prim) {
  frame.object[frame.index(i, j)] = object;
  frame.prim[frame.index(i, j)] = prim;
}

TEST(ImageDiff, IdenticalFramesHaveNoMismatch) {
  const Scene scene = test::analytic_scene({wall(), SharedEdge().object()});
  const CameraSpaceScene cs = CameraSpaceScene::build(scene);
  const Frame frame = test::exact_frame(cs, kSize, kSize, 0);
  FrameComparator comparator(cs);
  const FrameDiff diff = comparator.compare(frame, frame);
  EXPECT_EQ(diff.mismatch_real, 0u);
  EXPECT_EQ(diff.mismatch_tie, 0u);
  EXPECT_EQ(diff.pixel_count(), size_t(kSize * kSize));
  for (PixelClass c : diff.pixels) EXPECT_EQ(c, PixelClass::kEqual);
  const ColorError color = compare_colors(frame, frame);
  EXPECT_EQ(color.max_error, 0.0);
  EXPECT_FALSE(color.psnr().has_value());
}

TEST(ImageDiff, CorruptedFrameIsCaughtAndItsHeatMapWritten) {
  // A quad at depth 2..4 in front of the wall at depth 10; five pixels inside the quad are
  // corrupted to show the wall, far behind: five real mismatches, nothing else.
  const Vec3 tl = on_ray(8, 2, 2.0, kSize, kSize), tr = on_ray(24, 2, 3.0, kSize, kSize);
  const Vec3 br = on_ray(24, 14, 4.0, kSize, kSize), bl = on_ray(8, 14, 2.5, kSize, kSize);
  const Object quad = test::camera_space_object("quad", {{0, 1, 2}, {0, 2, 3}}, {{tl, tr, br, bl}});
  const Scene scene = test::analytic_scene({wall(), quad});
  const CameraSpaceScene cs = CameraSpaceScene::build(scene);
  const Frame reference = test::exact_frame(cs, kSize, kSize, 0);
  Frame tested = reference;
  const int corrupted[5][2] = {{9, 3}, {12, 5}, {16, 8}, {20, 11}, {23, 13}};
  for (const auto& ij : corrupted) {
    ASSERT_EQ(reference.object[reference.index(ij[0], ij[1])], 1u);
    set_pixel(tested, ij[0], ij[1], 0, 0);
  }
  FrameComparator comparator(cs);
  const FrameDiff diff = comparator.compare(tested, reference);
  EXPECT_EQ(diff.mismatch_real, 5u);
  EXPECT_EQ(diff.mismatch_tie, 0u);
  EXPECT_EQ(diff.cracks, 0u);

  const std::string path = ::testing::TempDir() + "/kinray_corrupted_diff.png";
  std::filesystem::remove(path);
  write_heat_map(diff, path);
  const cv::Mat image = cv::imread(path, cv::IMREAD_COLOR);
  ASSERT_FALSE(image.empty());
  ASSERT_EQ(image.cols, kSize);
  ASSERT_EQ(image.rows, kSize);
  for (const auto& ij : corrupted)
    EXPECT_EQ(image.at<cv::Vec3b>(ij[1], ij[0]), cv::Vec3b(0, 0, 255));  // red
  EXPECT_EQ(image.at<cv::Vec3b>(0, 0), cv::Vec3b(0, 0, 0));   // equal: the wall on both sides
  EXPECT_EQ(image.at<cv::Vec3b>(3, 10), cv::Vec3b(0, 0, 0));  // equal: the quad on both sides
}

TEST(ImageDiff, SharedEdgeThroughPixelCentreIsATie) {
  const SharedEdge pair;
  const Scene scene = test::analytic_scene({wall(), pair.object()});
  CameraSpaceScene cs = CameraSpaceScene::build(scene);
  set_positions(cs, 1, pair.exact());
  ASSERT_EQ(pair.p.cross(pair.q).dot(kRay), 0.0);
  ASSERT_EQ(PixelRays({kSize, kSize}).direction(kI, kJ), kRay);
  // One backend takes the left triangle, the other the right one.
  Frame tested = background_frame(), reference = background_frame();
  set_pixel(tested, kI, kJ, 1, 0);
  set_pixel(reference, kI, kJ, 1, 1);
  FrameComparator comparator(cs);
  const FrameDiff diff = comparator.compare(tested, reference);
  EXPECT_EQ(diff.mismatch_tie, 1u);
  EXPECT_EQ(diff.mismatch_real, 0u);
  EXPECT_EQ(diff.pixels[tested.index(kI, kJ)], PixelClass::kTie);
}

TEST(ImageDiff, SilhouetteEdgeThroughPixelCentreIsATieWithWhatIsBehind) {
  // Only the left triangle: its edge p q is a silhouette, so the ray may see it or what is behind.
  const SharedEdge pair;
  const Object left = test::camera_space_object("left", {{0, 1, 2}}, {{pair.p, pair.q, pair.l}});
  const Scene scene = test::analytic_scene({wall(), left});
  CameraSpaceScene cs = CameraSpaceScene::build(scene);
  set_positions(cs, 1, {pair.p, pair.q, pair.l});
  FrameComparator comparator(cs);
  Frame tested = background_frame(), reference = background_frame();
  set_pixel(tested, kI, kJ, 1, 0);
  set_pixel(reference, kI, kJ, 0, 0);  // the wall behind
  const FrameDiff diff = comparator.compare(tested, reference);
  EXPECT_EQ(diff.mismatch_tie, 1u);
  EXPECT_EQ(diff.mismatch_real, 0u);
}

TEST(ImageDiff, ATieNeedsBothSidesToHitSomething) {
  // Nothing behind the triangles: one side seeing the background where the other hits a triangle
  // is real whatever the edge margins and depths -- on a silhouette edge, at a vertex, inside, and
  // on a sliver seen edge-on (every edge within the tolerance of the ray).
  const SharedEdge pair;
  const PixelRays image{kSize, kSize};
  const Vec3 corner = 3 * image.direction(20, 20);  // a vertex exactly on the ray of (20, 20)
  const std::vector<Vec3> left{pair.p, pair.q, pair.l},
      corner_triangle{corner, corner + Vec3(1, 0, 0), corner + Vec3(0, -1, 0)},
      sliver{3 * kRay, 3 * kRay + Vec3(1e-9, 0, 0), 3 * kRay + Vec3(0, 0, 1e12)};
  const Scene scene =
      test::analytic_scene({test::camera_space_object("left", {{0, 1, 2}}, {left}),
                            test::camera_space_object("corner", {{0, 1, 2}}, {corner_triangle}),
                            test::camera_space_object("sliver", {{0, 1, 2}}, {sliver})});
  CameraSpaceScene cs = CameraSpaceScene::build(scene);
  set_positions(cs, 0, left);
  set_positions(cs, 1, corner_triangle);
  set_positions(cs, 2, sliver);
  const Frame exact = test::exact_frame(cs, kSize, kSize, 0);
  ASSERT_EQ(exact.object[exact.index(9, kJ)], 0u);  // inside the left triangle
  // {i, j, object}: the silhouette edge, the vertex, the interior, the sliver.
  const int cases[4][3] = {{kI, kJ, 0}, {20, 20, 1}, {9, kJ, 0}, {kI, kJ, 2}};
  FrameComparator comparator(cs);
  for (const auto& c : cases)
    for (const bool tested_hits : {true, false}) {
      SCOPED_TRACE(::testing::Message() << "pixel " << c[0] << "," << c[1] << " object " << c[2]);
      Frame hit = background_frame(), miss = background_frame();
      set_pixel(hit, c[0], c[1], uint32_t(c[2]), 0);
      const FrameDiff diff =
          tested_hits ? comparator.compare(hit, miss) : comparator.compare(miss, hit);
      EXPECT_EQ(diff.mismatch_real, 1u);
      EXPECT_EQ(diff.mismatch_tie, 0u);
      EXPECT_EQ(diff.pixels[hit.index(c[0], c[1])], PixelClass::kReal);
    }
  // Both hitting, the sliver against the left triangle stays a tie: same depth 3, on their edges.
  Frame sliver_frame = background_frame(), left_frame = background_frame();
  set_pixel(sliver_frame, kI, kJ, 2, 0);
  set_pixel(left_frame, kI, kJ, 0, 0);
  EXPECT_EQ(comparator.compare(sliver_frame, left_frame).mismatch_tie, 1u);
}

TEST(ImageDiff, LeakThroughAClosedEdgeIsACrack) {
  // Both triangles of the pair cover the ray between them; a backend that sees the wall through
  // their shared edge has a crack, a real mismatch.
  const SharedEdge pair;
  const Scene scene = test::analytic_scene({wall(), pair.object()});
  CameraSpaceScene cs = CameraSpaceScene::build(scene);
  set_positions(cs, 1, pair.exact());
  Frame tested = background_frame(), reference = background_frame();
  set_pixel(tested, kI, kJ, 0, 0);
  set_pixel(reference, kI, kJ, 1, 0);
  FrameComparator comparator(cs);
  FrameDiff diff = comparator.compare(tested, reference);
  EXPECT_EQ(diff.mismatch_real, 1u);
  EXPECT_EQ(diff.cracks, 1u);
  set_pixel(tested, kI, kJ, kNoHit, kNoHit);
  diff = comparator.compare(tested, reference);
  EXPECT_EQ(diff.mismatch_real, 1u);
  EXPECT_EQ(diff.cracks, 1u);
}

TEST(ImageDiff, DuplicateAcrossAFoldIsNoCrack) {
  // A fold: L rises towards the viewer on its side of the edge p q, R is flat at depth 3, and R2
  // (another object) duplicates R. The edge runs 5e-5 left of the ray, so the ray misses L by a
  // hair, hits R, and L's plane is nearer there than R by more than the depth tolerance. A
  // backend reporting L and one reporting R2 disagree only by float rounding: a tie. A backend
  // reporting what lies behind the fold, or the background, leaked: a crack.
  const Vec3 shift(-5e-5, 0, 0);
  const Vec3 p = 3 * kRay + Vec3(0, 0.5, 0) + shift, q = 3 * kRay - Vec3(0, 0.5, 0) + shift;
  const Vec3 l = 3 * kRay + Vec3(-0.5, 0, 0.5), r = 3 * kRay + Vec3(0.5, 0, 0);
  const Object fold = test::camera_space_object("fold", {{0, 1, 2}, {1, 0, 3}}, {{p, q, l, r}});
  const Object copy = test::camera_space_object("copy", {{1, 0, 2}}, {{p, q, r}});
  const Scene scene = test::analytic_scene({wall(), fold, copy});
  CameraSpaceScene cs = CameraSpaceScene::build(scene);
  set_positions(cs, 1, {p, q, l, r});
  set_positions(cs, 2, {p, q, r});
  const double z_left = test::plane_depth(p, q, l, kRay),
               z_right = test::plane_depth(q, p, r, kRay);
  ASSERT_LT(z_left, z_right - 1e-5 * z_right);  // beyond the depth tolerance (1/cos < 3 here)
  ASSERT_LT(p.cross(q).dot(kRay) * p.dot(q.cross(l)), 0.0);  // the ray is outside L, on R's side

  FrameComparator comparator(cs);
  Frame tested = background_frame(), reference = background_frame();
  set_pixel(tested, kI, kJ, 1, 0);     // L
  set_pixel(reference, kI, kJ, 2, 0);  // R2
  FrameDiff diff = comparator.compare(tested, reference);
  EXPECT_EQ(diff.mismatch_tie, 1u);
  EXPECT_EQ(diff.cracks, 0u);
  set_pixel(reference, kI, kJ, 0, 0);  // the wall behind
  diff = comparator.compare(tested, reference);
  EXPECT_EQ(diff.mismatch_real, 1u);
  EXPECT_EQ(diff.cracks, 1u);
}

TEST(ImageDiff, CoplanarTrianglesAreATie) {
  // Two objects with the same triangle: equal depth everywhere, no winner.
  const Vec3 a = on_ray(4, 4, 5, kSize, kSize), b = on_ray(28, 4, 5, kSize, kSize),
             c = on_ray(4, 28, 5, kSize, kSize);
  const Object one = test::camera_space_object("one", {{0, 1, 2}}, {{a, b, c}});
  const Object two = test::camera_space_object("two", {{0, 1, 2}}, {{a, c, b}});
  const Scene scene = test::analytic_scene({one, two});
  const CameraSpaceScene cs = CameraSpaceScene::build(scene);
  Frame tested = test::exact_frame(cs, kSize, kSize, 0);
  Frame reference = tested;
  size_t covered = 0;
  for (size_t p = 0; p < tested.pixel_count(); ++p)
    if (tested.object[p] != kNoHit) {
      tested.object[p] = 0;
      reference.object[p] = 1;
      ++covered;
    }
  ASSERT_GT(covered, 100u);
  FrameComparator comparator(cs);
  const FrameDiff diff = comparator.compare(tested, reference);
  EXPECT_EQ(diff.mismatch_tie, covered);
  EXPECT_EQ(diff.mismatch_real, 0u);
}

TEST(ImageDiff, MissingTheInteriorOfANearerTriangleIsReal) {
  // The ray runs exactly along an edge of a far triangle (depth 10) but through the middle of a
  // near one (depth 3): reporting the far one is wrong, however close it is to its own edge.
  const Vec3 near_a = 3 * kRay + Vec3(-1, -1, 0), near_b = 3 * kRay + Vec3(1, -1, 0),
             near_c = 3 * kRay + Vec3(0, 1, 0);
  const Vec3 far_p = 10 * kRay + Vec3(0, 1, 0), far_q = 10 * kRay - Vec3(0, 1, 0),
             far_r = 10 * kRay + Vec3(-1, 0, 0);
  const Object near = test::camera_space_object("near", {{0, 1, 2}}, {{near_a, near_b, near_c}});
  const Object far = test::camera_space_object("far", {{0, 1, 2}}, {{far_p, far_q, far_r}});
  const Scene scene = test::analytic_scene({near, far});
  CameraSpaceScene cs = CameraSpaceScene::build(scene);
  set_positions(cs, 0, {near_a, near_b, near_c});
  set_positions(cs, 1, {far_p, far_q, far_r});
  Frame tested = background_frame(), reference = background_frame();
  set_pixel(tested, kI, kJ, 1, 0);
  set_pixel(reference, kI, kJ, 0, 0);
  FrameComparator comparator(cs);
  EXPECT_EQ(comparator.compare(tested, reference).mismatch_real, 1u);
}

TEST(ImageDiff, ATriangleTheRayMissesIsReal) {
  const SharedEdge pair;
  const Scene scene = test::analytic_scene({wall(), pair.object()});
  CameraSpaceScene cs = CameraSpaceScene::build(scene);
  set_positions(cs, 1, pair.exact());
  Frame tested = test::exact_frame(cs, kSize, kSize, 0);
  Frame reference = tested;
  // Pixel (0, 31) sees only the wall; claiming the pair's triangle there is wrong, and so is
  // claiming an object or prim that does not exist.
  set_pixel(tested, 0, 31, 1, 0);
  set_pixel(tested, 31, 31, 7, 0);
  set_pixel(tested, 31, 0, 0, 5);
  FrameComparator comparator(cs);
  const FrameDiff diff = comparator.compare(tested, reference);
  EXPECT_EQ(diff.mismatch_real, 3u);
  EXPECT_EQ(diff.mismatch_tie, 0u);
}

TEST(ImageDiff, FramesMustMatchInSizeAndTime) {
  const Scene scene = test::analytic_scene({wall()});
  const CameraSpaceScene cs = CameraSpaceScene::build(scene);
  FrameComparator comparator(cs);
  Frame small;
  small.resize(8, 8);
  EXPECT_THROW((void)comparator.compare(background_frame(), small), std::invalid_argument);
  EXPECT_THROW((void)comparator.compare(background_frame(0), background_frame(0.5)),
               std::invalid_argument);
  EXPECT_THROW((void)compare_colors(background_frame(), small), std::invalid_argument);
}

TEST(ImageDiff, ColorErrorGivesPsnrAndMaximum) {
  Frame a = background_frame(), b = background_frame();
  b.color[5] = Color(0.5f, 0, 0);
  const ColorError error = compare_colors(a, b);
  EXPECT_DOUBLE_EQ(error.max_error, 0.5);
  // One channel of 3 * 1024 is off by 0.5: MSE = 0.25 / 3072.
  ASSERT_TRUE(error.psnr().has_value());
  EXPECT_NEAR(*error.psnr(), 10 * std::log10(3072 / 0.25), 1e-9);
}

TEST(ImageDiff, SummaryTotalsPrintsAndWritesJson) {
  DiffSummary summary;
  summary.scene = "analytic";
  summary.tested = "kinetic";
  summary.reference = "embree";
  FrameDiffSummary first;
  first.frame = 0;
  first.time = 0;
  first.pixels = 1024;
  first.mismatch_real = 2;
  first.mismatch_tie = 5;
  first.heat_map = "report/frame_0000.png";
  first.color = ColorError{.max_error = 0.25, .mse = 1e-4};
  FrameDiffSummary second;
  second.frame = 1;
  second.time = 0.5;
  second.pixels = 1024;
  second.mismatch_real = 0;
  second.mismatch_tie = 3;
  second.color = ColorError{};
  summary.add(first);
  summary.add(second);
  EXPECT_EQ(summary.frames, 2u);
  EXPECT_EQ(summary.pixels, 2048u);
  EXPECT_EQ(summary.mismatch_real, 2u);
  EXPECT_EQ(summary.mismatch_tie, 8u);
  EXPECT_EQ(summary.max_frame_real(), 2u);

  std::ostringstream table;
  summary.print(table);
  EXPECT_NE(table.str().find("report/frame_0000.png"), std::string::npos);
  EXPECT_NE(table.str().find("2 real mismatches"), std::string::npos);
  EXPECT_NE(table.str().find("inf"), std::string::npos);  // identical colours in frame 1

  const std::string path = ::testing::TempDir() + "/kinray_diff_summary.json";
  summary.write_json(path);
  std::ifstream file(path);
  const nlohmann::json json = nlohmann::json::parse(file);
  EXPECT_EQ(json["frames"], 2);
  EXPECT_EQ(json["pixels"], 2048);
  EXPECT_EQ(json["mismatch_real"], 2);
  EXPECT_EQ(json["mismatch_tie"], 8);
  ASSERT_EQ(json["per_frame"].size(), 2u);
  EXPECT_EQ(json["per_frame"][0]["heat_map"], "report/frame_0000.png");
  EXPECT_NEAR(json["per_frame"][0]["psnr"].get<double>(), 40.0, 1e-9);
  EXPECT_TRUE(json["per_frame"][1]["psnr"].is_null());
  EXPECT_TRUE(json["per_frame"][1]["heat_map"].is_null());
  EXPECT_EQ(json["per_frame"][1]["time"], 0.5);

  // A failed write is the machine's failure (exit 1), not bad input: commands check paths first.
  EXPECT_THROW(summary.write_json("/nonexistent-dir/summary.json"), std::runtime_error);
  FrameDiff diff;
  diff.width = diff.height = 1;
  diff.pixels = {PixelClass::kReal};
  EXPECT_THROW(write_heat_map(diff, "/nonexistent-dir/diff.png"), InputError);
}

}  // namespace
}  // namespace kinray
