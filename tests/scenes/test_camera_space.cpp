// Camera space (docs/design.md): the transform of world points, checked against values computed by
// hand; the fov folding; the key grid of an object under a moving camera; pixel-centre rays.
//
// The world is right-handed (as glTF, COLLADA, OBJ and assimp's output are): a camera looking
// down +z with +y up has world -x on its right. So a camera at (0, 0, 5) looking at the origin
// sees world (1, 0, 0) on the right, and a camera at (0, 0, -5) sees it on the left.
#include <gtest/gtest.h>

#include <cmath>

#include "scenes/camera_space.h"

namespace kinray {
namespace {

/// One static triangle with world vertices a, b, c, seen by `camera`.
Scene triangle_scene(const Vec3& a, const Vec3& b, const Vec3& c, const Camera& camera) {
  Scene scene;
  Object object;
  object.triangles = {{0, 1, 2}};
  object.key_times = {0};
  object.key_positions = {{a, b, c}};
  scene.objects.push_back(object);
  scene.camera = camera;
  scene.validate("test");
  return scene;
}

Camera fixed(const Vec3& eye, double fov = 90) {
  Camera camera;
  camera.keys = {Camera::look_at(0, eye, Vec3::Zero(), Vec3::UnitY(), fov)};
  return camera;
}

void expect_near(const Vec3& actual, const Vec3& expected, double tolerance = 1e-12) {
  EXPECT_NEAR((actual - expected).norm(), 0.0, tolerance)
      << "actual (" << actual.transpose() << "), expected (" << expected.transpose() << ")";
}

TEST(CameraSpace, LookAtFromThePositiveZSide) {
  // fov 90: tan(45 deg) = 1, so no folding. Camera at (0, 0, 5) looking at the origin.
  const Scene scene =
      triangle_scene(Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 0), fixed(Vec3(0, 0, 5)));
  const CameraSpaceScene cs = CameraSpaceScene::build(scene);
  ASSERT_EQ(cs.objects.size(), 1u);
  EXPECT_TRUE(cs.objects[0].is_static);
  expect_near(cs.objects[0].position(0, 0), Vec3(1, 0, 5));  // right of the centre, 5 in front
  expect_near(cs.objects[0].position(1, 0), Vec3(0, 1, 5));  // above
  expect_near(cs.objects[0].position(2, 0), Vec3(0, 0, 5));  // the target: on the axis
}

TEST(CameraSpace, LookAtFromTheNegativeZSideMirrorsX) {
  // Camera at (0, 0, -5) looking at the origin: depth 5, up stays up, and in a right-handed world
  // +x is on the viewer's left (camera-space x = -1).
  const Scene scene =
      triangle_scene(Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 2), fixed(Vec3(0, 0, -5)));
  const CameraSpaceScene cs = CameraSpaceScene::build(scene);
  expect_near(cs.objects[0].position(0, 0), Vec3(-1, 0, 5));
  expect_near(cs.objects[0].position(1, 0), Vec3(0, 1, 5));
  expect_near(cs.objects[0].position(2, 0), Vec3(0, 0, 7));  // farther along the view direction
}

TEST(CameraSpace, FovFoldsIntoXAndY) {
  // fov 60: x and y scaled by 1 / tan(30 deg) = sqrt(3); z untouched, so the ray parameter of a
  // hit is still the depth.
  const Scene scene =
      triangle_scene(Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 0), fixed(Vec3(0, 0, 5), 60));
  const CameraSpaceScene cs = CameraSpaceScene::build(scene);
  expect_near(cs.objects[0].position(0, 0), Vec3(std::sqrt(3.0), 0, 5));
  expect_near(cs.objects[0].position(1, 0), Vec3(0, std::sqrt(3.0), 5));
  EXPECT_NEAR(cs.tan_half_fov(0), 1 / std::sqrt(3.0), 1e-15);
  // The point at the top edge of the 60-degree view, (0, 5 tan 30, 0), lands on y/z = 1.
  const Scene edge = triangle_scene(Vec3(0, 5 * std::tan(M_PI / 6), 0), Vec3(1, 0, 0),
                                    Vec3(0, 0, 0), fixed(Vec3(0, 0, 5), 60));
  const Vec3 top = CameraSpaceScene::build(edge).objects[0].position(0, 0);
  EXPECT_NEAR(top.y() / top.z(), 1.0, 1e-12);
}

TEST(CameraSpace, AnimatedCameraIsLinearInCameraSpaceBetweenKeys) {
  // The camera swings from (0, 0, 5) to (5, 0, 0), always looking at the origin, fov 60 -> 90.
  Camera camera;
  camera.keys = {Camera::look_at(0, Vec3(0, 0, 5), Vec3::Zero(), Vec3::UnitY(), 60),
                 Camera::look_at(1, Vec3(5, 0, 0), Vec3::Zero(), Vec3::UnitY(), 90)};
  const Scene scene = triangle_scene(Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 0), camera);
  const CameraSpaceScene cs = CameraSpaceScene::build(scene);
  const CameraSpaceObject& object = cs.objects[0];
  EXPECT_FALSE(object.is_static);
  ASSERT_EQ(object.key_times, (std::vector<double>{0, 1}));
  // Key 0: (1, 0, 0) on the right at depth 5, folded by sqrt(3).
  expect_near(object.position(0, 0), Vec3(std::sqrt(3.0), 0, 5));
  // Key 1: the camera at (5, 0, 0) looks down -x, its right is -z: (1, 0, 0) is dead ahead at
  // depth 4.
  expect_near(object.position(0, 1), Vec3(0, 0, 4));
  // In between: the straight line between the two camera-space keys (not the world motion).
  expect_near(object.position(0, 0.5), Vec3(std::sqrt(3.0) / 2, 0, 4.5));
  // The origin stays on the axis at depth 5 throughout.
  expect_near(object.position(2, 0.25), Vec3(0, 0, 5));
  // Outside the keys the motion stands still.
  expect_near(object.position(0, -3), object.position(0, 0));
  expect_near(object.position(0, 7), object.position(0, 1));
  EXPECT_NEAR(cs.tan_half_fov(0.5), std::tan(75.0 / 2 * M_PI / 180), 1e-15);

  std::vector<Vec3> all;
  object.positions_at(0.5, all);
  ASSERT_EQ(all.size(), 3u);
  expect_near(all[0], object.position(0, 0.5));
}

TEST(CameraSpace, ShortcutsForShadingAgreeBitForBitWithTheFullEvaluation) {
  // Motion blur shades at many times: tan_half_fov interpolates the fov without Camera::at, and
  // a ShadingInstant locates a time once for all vertices. Both must give the same bits.
  Camera camera;
  camera.keys = {Camera::look_at(0, Vec3(0, 0, 5), Vec3::Zero(), Vec3::UnitY(), 60),
                 Camera::look_at(0.7, Vec3(5, 0, 0), Vec3::Zero(), Vec3::UnitY(), 90),
                 Camera::look_at(1.3, Vec3(0, 3, 4), Vec3::Zero(), Vec3::UnitY(), 35)};
  const Scene scene = triangle_scene(Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 0), camera);
  const CameraSpaceScene cs = CameraSpaceScene::build(scene);
  const CameraSpaceObject& object = cs.objects[0];
  for (double t : {-1.0, 0.0, 0.1, 0.35, 0.7, 0.71, 1.0, 1.3, 2.0}) {
    EXPECT_EQ(cs.tan_half_fov(t), std::tan(camera.at(t).fov_y_degrees * M_PI / 360.0)) << t;
    const KeySegment at = locate(object.key_times, t);
    for (uint32_t v = 0; v < 3; ++v) {
      EXPECT_EQ(object.position(v, at), object.position(v, t)) << t;
      EXPECT_EQ(object.normal(v, at), object.normal(v, t)) << t;
    }
  }
  EXPECT_NE(cs.tan_half_fov(0.35), cs.tan_half_fov(1.0));  // the fov does move
  EXPECT_FALSE(cs.fixed_tan_half_fov());

  // One fov at every key: its tangent at every time, bit for bit.
  for (auto& key : camera.keys) key.fov_y_degrees = 47;
  const CameraSpaceScene still_fov =
      CameraSpaceScene::build(triangle_scene(Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 0), camera));
  ASSERT_TRUE(still_fov.fixed_tan_half_fov());
  for (double t : {-1.0, 0.0, 0.35, 0.7, 1.0, 2.0})
    EXPECT_EQ(*still_fov.fixed_tan_half_fov(), still_fov.tan_half_fov(t)) << t;
}

TEST(CameraSpace, LocateWithTheFirstKeyAboveGivenIsLocate) {
  // Motion blur's nodes know the piece of the key grid they lie in (for_each_node): the segment
  // and alpha are locate()'s, bit for bit, inside the piece, at its keys and beyond the grid.
  const std::vector<double> times = {0, 0.1, 1.0 / 3, 1, 3};
  for (size_t next = 0; next <= times.size(); ++next) {
    const double lo = next == 0 ? -1 : times[next - 1], hi = next == times.size() ? 4 : times[next];
    for (int k = 0; k <= 16; ++k) {
      const double t = lo + (hi - lo) * k / 16;
      const KeySegment expected = locate(times, t), got = locate(times, t, next);
      EXPECT_EQ(got.k, expected.k) << t;
      EXPECT_EQ(got.alpha, expected.alpha) << t;
    }
  }
}

TEST(CameraSpace, KeyGridIsTheUnionOfObjectAndCameraKeys) {
  Scene scene;
  Object moving;
  moving.triangles = {{0, 1, 2}};
  moving.key_times = {0, 0.5, 2};
  moving.key_positions = {{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)},
                          {Vec3(0, 0, 1), Vec3(1, 0, 1), Vec3(0, 1, 1)},
                          {Vec3(0, 0, 2), Vec3(1, 0, 2), Vec3(0, 1, 2)}};
  Object still = moving;
  still.key_times = {0, 1};
  still.key_positions = {moving.key_positions[0], moving.key_positions[0]};  // keys, but no motion
  scene.objects = {moving, still};
  scene.camera.keys = {Camera::look_at(0, Vec3(0, 0, -5), Vec3::Zero(), Vec3::UnitY(), 45),
                       Camera::look_at(1, Vec3(1, 0, -5), Vec3::Zero(), Vec3::UnitY(), 45)};
  scene.time_end = 2;
  scene.validate("test");
  const CameraSpaceScene cs = CameraSpaceScene::build(scene);
  EXPECT_EQ(cs.objects[0].key_times, (std::vector<double>{0, 0.5, 1, 2}));
  EXPECT_EQ(cs.objects[1].key_times, (std::vector<double>{0, 1}));  // the camera's keys only
  // At the object's own key 0.5 the camera is halfway: world point (0,0,1) seen from (0.5,0,-5).
  const Vec3 eye(0.5, 0, -5);
  const CameraKey halfway = scene.camera.at(0.5);
  EXPECT_NEAR((halfway.position - eye).norm(), 0, 1e-15);
  EXPECT_EQ(scene.key_times(), (std::vector<double>{0, 0.5, 1, 2}));

  scene.camera.keys.resize(1);
  const CameraSpaceScene fixed_camera = CameraSpaceScene::build(scene);
  EXPECT_EQ(fixed_camera.objects[0].key_times, (std::vector<double>{0, 0.5, 2}));
  EXPECT_EQ(fixed_camera.objects[1].key_times, (std::vector<double>{0}));
  EXPECT_TRUE(fixed_camera.objects[1].is_static);
}

TEST(CameraSpace, AShortSpanKeepsTheKeysItNeedsAndTheSamePositionsInside) {
  Scene scene;
  Object moving;
  moving.triangles = {{0, 1, 2}};
  for (int k = 0; k <= 10; ++k) {
    moving.key_times.push_back(0.1 * k);
    const double z = 1 + 0.3 * k + 0.01 * k * k;  // a different speed on every segment
    moving.key_positions.push_back({Vec3(0, 0, z), Vec3(1, 0.1 * k, z), Vec3(0, 1, z)});
  }
  scene.objects = {moving};
  scene.camera.keys = {Camera::look_at(0, Vec3(0, 0, -5), Vec3::Zero(), Vec3::UnitY(), 45),
                       Camera::look_at(1, Vec3(1, 0, -5), Vec3::Zero(), Vec3::UnitY(), 45)};
  scene.validate("test");
  const CameraSpaceScene all = CameraSpaceScene::build(scene);
  const CameraSpaceScene part = CameraSpaceScene::build(scene, std::pair(0.25, 0.5));
  // 0.2 is the last key before the span, 0.5 the first at its end.
  EXPECT_EQ(part.objects[0].key_times, (std::vector<double>{0.1 * 2, 0.1 * 3, 0.1 * 4, 0.1 * 5}));
  EXPECT_EQ(part.objects[0].positions.size(), 4u * 3u);
  for (double t : {0.25, 0.3, 0.31, 0.4, 0.499, 0.5})
    for (uint32_t v = 0; v < 3; ++v) {
      EXPECT_EQ(part.objects[0].position(v, t), all.objects[0].position(v, t)) << t;
      EXPECT_EQ(part.objects[0].normal(v, t), all.objects[0].normal(v, t)) << t;
    }
  // A span on keys keeps them; one beyond every key keeps the last, where the object stands.
  EXPECT_EQ(CameraSpaceScene::build(scene, std::pair(0.1 * 3, 0.1 * 4)).objects[0].key_times,
            (std::vector<double>{0.1 * 3, 0.1 * 4}));
  const CameraSpaceScene after = CameraSpaceScene::build(scene, std::pair(2.0, 3.0));
  EXPECT_EQ(after.objects[0].key_times, (std::vector<double>{1}));
  EXPECT_TRUE(after.objects[0].is_static);
  EXPECT_EQ(after.objects[0].position(1, 2.5), all.objects[0].position(1, 2.5));
}

TEST(CameraSpace, NormalsAreUnitAndPerpendicular) {
  const Scene scene =
      triangle_scene(Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1), fixed(Vec3(3, 4, 5)));
  const CameraSpaceScene cs = CameraSpaceScene::build(scene);
  const CameraSpaceObject& object = cs.objects[0];
  const Vec3 e1 = object.position(1, 0) - object.position(0, 0),
             e2 = object.position(2, 0) - object.position(0, 0);
  for (uint32_t v = 0; v < 3; ++v) {
    const Eigen::Vector3f n = object.normal(v, 0);
    EXPECT_NEAR(n.norm(), 1.0f, 1e-6f);
    // fov 90 means no folding, so camera-space edges are true edges.
    EXPECT_NEAR(n.cast<double>().dot(e1), 0, 1e-6);
    EXPECT_NEAR(n.cast<double>().dot(e2), 0, 1e-6);
  }
}

TEST(CameraSpace, LocateOnTheKeyGrid) {
  const std::vector<double> times = {0, 1, 3};
  auto check = [&](double t, size_t k, double alpha) {
    const KeySegment s = locate(times, t);
    EXPECT_EQ(s.k, k) << t;
    EXPECT_DOUBLE_EQ(s.alpha, alpha) << t;
  };
  check(-1, 0, 0);
  check(0, 0, 0);
  check(0.5, 0, 0.5);
  check(1, 1, 0);
  check(2, 1, 0.5);
  check(3, 1, 1);
  check(9, 1, 1);
  const std::vector<double> single = {4};
  EXPECT_EQ(locate(single, 10).k, 0u);
  EXPECT_EQ(locate(single, 10).alpha, 0.0);
}

TEST(CameraSpace, PixelCentreRays) {
  const PixelRays image{4, 2};
  // Aspect 2: x spans [-2, 2] over the image width, y spans [-1, 1]; row 0 at the top.
  EXPECT_DOUBLE_EQ(image.x(0), -1.5);
  EXPECT_DOUBLE_EQ(image.x(3), 1.5);
  EXPECT_DOUBLE_EQ(image.y(0), 0.5);
  EXPECT_DOUBLE_EQ(image.y(1), -0.5);
  EXPECT_EQ(image.direction(2, 1), Vec3(0.5, -0.5, 1));
  EXPECT_EQ(image.pixel_count(), 8u);
  // A point on the right of a camera lands in the right half of the image.
  const Scene scene =
      triangle_scene(Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 0), fixed(Vec3(0, 0, 5), 45));
  const Vec3 p = CameraSpaceScene::build(scene).objects[0].position(0, 0);
  EXPECT_GT(p.x() / p.z(), 0);
}

}  // namespace
}  // namespace kinray
