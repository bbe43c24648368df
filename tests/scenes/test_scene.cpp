// The scene model: flightplan interpolation, the camera's keys, validation, textures.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <memory>

#include "scenes/scene.h"
#include "util/input_error.h"

namespace kinray {
namespace {

Object sliding_triangle() {
  Object object;
  object.name = "slider";
  object.triangles = {{0, 1, 2}};
  object.key_times = {0, 2, 3};
  object.key_positions = {{Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)},
                          {Vec3(3, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)},
                          {Vec3(3, 4, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)}};
  return object;
}

Scene one_object_scene(const Object& object) {
  Scene scene;
  scene.objects = {object};
  scene.time_end = 3;
  return scene;
}

/// The message of the InputError that validating `scene` throws.
std::string validation_error(const Scene& scene) {
  try {
    scene.validate("scene.json");
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find("scene.json"), std::string::npos);
    return error.what();
  }
  ADD_FAILURE() << "no InputError";
  return "";
}

TEST(Scene, FlightplansArePiecewiseLinearAndStandStillOutside) {
  const Object object = sliding_triangle();
  EXPECT_EQ(object.position(0, 0), Vec3(1, 0, 0));
  EXPECT_EQ(object.position(0, 0.5), Vec3(1.5, 0, 0));  // a quarter of the way from 1 to 3
  EXPECT_EQ(object.position(0, 2), Vec3(3, 0, 0));
  EXPECT_EQ(object.position(0, 2.25), Vec3(3, 1, 0));
  EXPECT_EQ(object.position(0, -10), Vec3(1, 0, 0));
  EXPECT_EQ(object.position(0, 10), Vec3(3, 4, 0));
  EXPECT_EQ(object.position(2, 1.7), Vec3(0, 0, 1));
  EXPECT_FALSE(object.is_static());
  EXPECT_EQ(object.vertex_count(), 3u);
  EXPECT_EQ(object.key_count(), 3u);

  Object still = object;
  still.key_positions = {object.key_positions[0], object.key_positions[0], object.key_positions[0]};
  EXPECT_TRUE(still.is_static());
  Object single = object;
  single.key_times = {5};
  single.key_positions = {object.key_positions[1]};
  EXPECT_TRUE(single.is_static());
  EXPECT_EQ(single.position(0, -1), Vec3(3, 0, 0));
}

/// The sliding triangle's first key moved rigidly: at key k (time k), turned by degrees[k]
/// about z and shifted by k along x.
Object rigid_triangle(const std::vector<double>& degrees) {
  Object object = sliding_triangle();
  auto transforms = std::make_shared<std::vector<Eigen::Affine3d>>();
  object.key_times.clear();
  for (size_t k = 0; k < degrees.size(); ++k) {
    object.key_times.push_back(double(k));
    transforms->push_back(Eigen::Translation3d(double(k), 0, 0) *
                          Eigen::AngleAxisd(degrees[k] * M_PI / 180, Vec3::UnitZ()));
  }
  object.rigid = RigidKeys{object.key_positions[0], transforms};
  object.key_positions.clear();
  return object;
}

TEST(Scene, RigidKeysMoveTheVerticesAsTheSameExplicitKeysWould) {
  const Object rigid = rigid_triangle({0, 90, 180});
  Object explicit_keys = rigid;
  explicit_keys.make_keys_explicit();
  ASSERT_FALSE(explicit_keys.rigid);
  ASSERT_EQ(explicit_keys.key_positions.size(), 3u);
  EXPECT_EQ(rigid.vertex_count(), 3u);
  EXPECT_EQ(rigid.key_position_sets(), 3u);
  // (1, 0, 0) turned a quarter about z, then shifted by 1 along x.
  EXPECT_NEAR((rigid.key_position(1, 0) - Vec3(1, 1, 0)).norm(), 0, 1e-15);
  for (double t : {-1.0, 0.0, 0.3, 1.0, 1.7, 9.0})
    for (uint32_t v = 0; v < 3; ++v) EXPECT_EQ(rigid.position(v, t), explicit_keys.position(v, t));
  EXPECT_FALSE(rigid.is_static());
  EXPECT_NO_THROW(one_object_scene(rigid).validate("scene.json"));
  EXPECT_EQ(one_object_scene(rigid).bounds().min(), one_object_scene(explicit_keys).bounds().min());
  EXPECT_EQ(one_object_scene(rigid).bounds().max(), one_object_scene(explicit_keys).bounds().max());

  // Equal transforms leave it still; so does a turn about an axis through every vertex.
  Object still = rigid_triangle({30, 30, 30});
  still.rigid->transforms =
      std::make_shared<std::vector<Eigen::Affine3d>>(3, (*still.rigid->transforms)[0]);
  EXPECT_TRUE(still.is_static());
  Object spun = rigid_triangle({0, 0});
  spun.rigid->positions = {Vec3(0, 0, 1), Vec3(0, 0, 2), Vec3(0, 0, 3)};
  spun.rigid->transforms =
      std::make_shared<std::vector<Eigen::Affine3d>>(std::vector<Eigen::Affine3d>{
          Eigen::Affine3d::Identity(), Eigen::Affine3d(Eigen::AngleAxisd(1.0, Vec3::UnitZ()))});
  EXPECT_TRUE(spun.is_static());
}

TEST(Scene, ARigidKeyBeyondTheLargestCoordinateIsRefusedWithItsVertexAndKey) {
  Object far = rigid_triangle({0, 0, 0});
  auto transforms = std::make_shared<std::vector<Eigen::Affine3d>>(*far.rigid->transforms);
  (*transforms)[2] = Eigen::Translation3d(0, 2e15, 0) * (*transforms)[2];
  far.rigid->transforms = transforms;
  const std::string message = validation_error(one_object_scene(far));
  EXPECT_NE(message.find("vertex 0 at key 2 has a coordinate beyond +-1e15"), std::string::npos)
      << message;
}

TEST(Scene, FlightplanUpdatesAreValidated) {
  Object object = sliding_triangle();
  object.set_flightplans({0, 1}, {object.key_positions[0], object.key_positions[2]});
  EXPECT_EQ(object.position(0, 0.5), Vec3(2, 2, 0));
  // A bad update throws and leaves the flightplans as they were.
  EXPECT_THROW(object.set_flightplans({1, 0}, {object.key_positions[0], object.key_positions[1]}),
               InputError);
  EXPECT_THROW(object.set_flightplans({0, 1}, {object.key_positions[0]}), InputError);
  EXPECT_EQ(object.key_times, (std::vector<double>{0, 1}));
  EXPECT_EQ(object.position(0, 0.5), Vec3(2, 2, 0));
}

TEST(Scene, CameraKeysInterpolate) {
  Camera camera;
  camera.keys = {Camera::look_at(0, Vec3(0, 0, 5), Vec3::Zero(), Vec3::UnitY(), 40),
                 Camera::look_at(2, Vec3(5, 0, 0), Vec3::Zero(), Vec3::UnitY(), 60)};
  const CameraKey middle = camera.at(1);
  EXPECT_EQ(middle.time, 1);
  EXPECT_EQ(middle.position, Vec3(2.5, 0, 2.5));
  EXPECT_DOUBLE_EQ(middle.fov_y_degrees, 50);
  // Slerp: halfway through a quarter turn about +y.
  const Eigen::Quaterniond eighth(Eigen::AngleAxisd(M_PI / 4, Vec3::UnitY()));
  EXPECT_NEAR(middle.orientation.angularDistance(eighth), 0, 1e-12);
  EXPECT_EQ(camera.at(-1).position, Vec3(0, 0, 5));
  EXPECT_EQ(camera.at(9).position, Vec3(5, 0, 0));
}

TEST(Scene, LookAtBuildsARightHandedFrame) {
  // From +z looking at the origin: the camera's own frame (right, up, back) is the world's axes.
  const CameraKey front = Camera::look_at(0, Vec3(0, 0, 5), Vec3::Zero(), Vec3::UnitY(), 45);
  EXPECT_NEAR(front.orientation.angularDistance(Eigen::Quaterniond::Identity()), 0, 1e-12);
  // From -z: turned half a turn about +y, so the camera's right is world -x.
  const CameraKey back = Camera::look_at(0, Vec3(0, 0, -5), Vec3::Zero(), Vec3::UnitY(), 45);
  EXPECT_NEAR((back.orientation * Vec3::UnitX() - Vec3(-1, 0, 0)).norm(), 0, 1e-12);
  EXPECT_NEAR((back.orientation * Vec3::UnitY() - Vec3(0, 1, 0)).norm(), 0, 1e-12);
  // Looking straight down along the up vector still gives an orthonormal frame.
  const CameraKey down = Camera::look_at(0, Vec3(0, 5, 0), Vec3::Zero(), Vec3::UnitY(), 45);
  EXPECT_TRUE(down.orientation.coeffs().allFinite());
  EXPECT_NEAR(down.orientation.norm(), 1, 1e-12);
  EXPECT_NEAR((down.orientation * Vec3::UnitZ() - Vec3(0, 1, 0)).norm(), 0,
              1e-12);  // back = up the y axis
}

TEST(Scene, ValidationNamesTheProblem) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_NO_THROW(one_object_scene(sliding_triangle()).validate("scene.json"));
  struct Case {
    const char* what;
    std::function<void(Scene&)> spoil;
    const char* problem;
  };
  const std::vector<Case> cases = {
      {"NaN vertex", [&](Scene& s) { s.objects[0].key_positions[1][2].y() = nan; },
       "vertex 2 at key 1 is NaN or infinite"},
      {"infinite vertex", [](Scene& s) { s.objects[0].key_positions[0][0].x() = kInfinity; },
       "NaN or infinite"},
      {"index out of range", [](Scene& s) { s.objects[0].triangles[0][1] = 3; },
       "vertex index 3 out of range (3 vertices)"},
      {"unsorted key times",
       [](Scene& s) {
         s.objects[0].key_times = {0, 2, 1};
       },
       "(unsorted)"},
      {"duplicate key times",
       [](Scene& s) {
         s.objects[0].key_times = {0, 2, 2};
       },
       "(duplicate)"},
      {"NaN key time", [&](Scene& s) { s.objects[0].key_times[1] = nan; },
       "key time 1 is not a finite number"},
      {"no keys", [](Scene& s) { s.objects[0].key_times.clear(); }, "no key times"},
      {"key count mismatch", [](Scene& s) { s.objects[0].key_positions.pop_back(); },
       "3 key times but 2 key position sets"},
      {"vertex count mismatch", [](Scene& s) { s.objects[0].key_positions[2].pop_back(); },
       "key 2 has 2 vertices, key 0 has 3"},
      {"uv count", [](Scene& s) { s.objects[0].uvs = {Vec2f(0, 0)}; }, "has 1 uvs for 3 vertices"},
      {"NaN uv",
       [](Scene& s) {
         s.objects[0].uvs = {Vec2f(0, 0), Vec2f(1, std::numeric_limits<float>::quiet_NaN()),
                             Vec2f(0, 1)};
       },
       "the texture coordinates of vertex 1 are NaN or infinite"},
      {"material index", [](Scene& s) { s.objects[0].material = 4; },
       "material index 4 out of range"},
      {"appear after disappear",
       [](Scene& s) {
         s.objects[0].appear = 2;
         s.objects[0].disappear = 1;
       },
       "must disappear after it appears"},
      {"empty shot", [](Scene& s) { s.time_end = s.time_begin; },
       "the shot must have finite times with end > begin"},
      {"NaN shot", [&](Scene& s) { s.time_begin = nan; }, "the shot must have finite times"},
      {"negative colour", [](Scene& s) { s.materials[0].base_color.x() = -0.5f; },
       "material 0 has an invalid base colour"},
      {"missing texture", [](Scene& s) { s.materials[0].texture = 0; },
       "material 0 names a missing texture"},
      {"no materials", [](Scene& s) { s.materials.clear(); }, "no materials"},
      {"fov", [](Scene& s) { s.camera.keys[0].fov_y_degrees = 180; },
       "fov_y must lie in (0.5, 179.5) degrees"},
      {"camera NaN", [&](Scene& s) { s.camera.keys[0].position.z() = nan; },
       "camera: a key has a NaN"},
      {"camera times",
       [](Scene& s) {
         s.camera.keys = {CameraKey{1}, CameraKey{0}};
       },
       "camera: key times must be strictly increasing"},
      {"no camera keys", [](Scene& s) { s.camera.keys.clear(); }, "camera: no key times"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.what);
    Scene scene = one_object_scene(sliding_triangle());
    c.spoil(scene);
    const std::string message = validation_error(scene);
    EXPECT_NE(message.find(c.problem), std::string::npos) << message;
  }
  // Object errors name the object.
  Scene scene = one_object_scene(sliding_triangle());
  scene.objects[0].triangles[0][0] = 7;
  EXPECT_NE(validation_error(scene).find("object 0 'slider'"), std::string::npos);
}

TEST(Scene, KeyTimesCountsAndBounds) {
  Scene scene = one_object_scene(sliding_triangle());
  Object fixed = sliding_triangle();
  fixed.key_times = {0.25, 0.75, 1.25};  // keyed, but never moving: no keyframes of its own
  fixed.key_positions = {fixed.key_positions[0], fixed.key_positions[0], fixed.key_positions[0]};
  scene.objects.push_back(fixed);
  scene.camera.keys = {CameraKey{0.5}, CameraKey{5}};
  scene.time_begin = 0.1;
  scene.time_end = 2.5;
  // Shot ends, the moving object's key 2 and the camera key 0.5; keys outside the shot are left
  // out.
  EXPECT_EQ(scene.key_times(), (std::vector<double>{0.1, 0.5, 2, 2.5}));
  EXPECT_EQ(scene.triangle_count(), 2u);
  EXPECT_EQ(scene.vertex_count(), 6u);
  EXPECT_EQ(scene.bounds().min(), Vec3(0, 0, 0));
  EXPECT_EQ(scene.bounds().max(), Vec3(3, 4, 1));
}

TEST(Scene, TextureSamplingIsBilinearAndWraps) {
  Texture texture;
  texture.width = 2;
  texture.height = 2;
  // Row 0 is the top (v = 1).
  texture.texels = {Color(1, 0, 0), Color(0, 1, 0), Color(0, 0, 1), Color(1, 1, 1)};
  EXPECT_EQ(texture.sample(Vec2f(0.25f, 0.75f)), Color(1, 0, 0));  // centre of the top-left texel
  EXPECT_EQ(texture.sample(Vec2f(0.75f, 0.25f)), Color(1, 1, 1));
  EXPECT_NEAR((texture.sample(Vec2f(0.5f, 0.5f)) - Color(0.5f, 0.5f, 0.5f)).norm(), 0, 1e-6);
  EXPECT_EQ(texture.sample(Vec2f(1.25f, -0.25f)), Color(1, 0, 0));  // wraps around
  EXPECT_EQ(Texture{}.sample(Vec2f(0.3f, 0.3f)), Color::Ones());    // no image: white
}

TEST(Scene, TexturePathAverageIsTheMeanOfTheSamplesAlongTheSegment) {
  // A 3 x 2 texture of distinct colours; segments across several texels, wrapping around,
  // against the mean of a million samples along them (the midpoint rule, error ~1e-12 here).
  Texture texture;
  texture.width = 3;
  texture.height = 2;
  texture.texels = {Color(1, 0, 0), Color(0, 1, 0), Color(0, 0, 1),
                    Color(1, 1, 0), Color(0, 1, 1), Color(0.2f, 0.4f, 0.9f)};
  const std::pair<Vec2f, Vec2f> segments[] = {{Vec2f(0.1f, 0.2f), Vec2f(0.9f, 0.7f)},
                                              {Vec2f(-0.3f, 1.4f), Vec2f(2.2f, -0.6f)},
                                              {Vec2f(0.4f, 0.1f), Vec2f(0.4f, 0.95f)},
                                              {Vec2f(0.52f, 0.5f), Vec2f(0.55f, 0.51f)}};
  for (const auto& [from, to] : segments) {
    Eigen::Vector3d mean = Eigen::Vector3d::Zero();
    const int n = 1 << 20;
    for (int k = 0; k < n; ++k) {
      const double s = (k + 0.5) / n;
      const Vec2f uv = (from.cast<double>() + s * (to - from).cast<double>()).cast<float>();
      mean += texture.sample(uv).cast<double>();
    }
    mean /= n;
    const Color average = texture.path_average(from, to);
    EXPECT_NEAR((average.cast<double>() - mean).cwiseAbs().maxCoeff(), 0, 2e-6)
        << from.transpose() << " -> " << to.transpose();
  }
  // Far from [0, 1) the texture repeats: a segment 2^20 periods away (its uvs exact in float)
  // averages as the one in the first period, and one across 1e30 of them (a malformed model) is
  // a finite colour.
  EXPECT_NEAR((texture.path_average(Vec2f(1048576.125f, 0.25f), Vec2f(1048576.875f, 0.75f)) -
               texture.path_average(Vec2f(0.125f, 0.25f), Vec2f(0.875f, 0.75f)))
                  .cwiseAbs()
                  .maxCoeff(),
              0, 1e-6);
  EXPECT_TRUE(texture.path_average(Vec2f(-1e30f, 0.5f), Vec2f(1e30f, 0.5f)).allFinite());
  // A segment of no length is the sample, bit for bit (a pixel nothing moves over stays sharp).
  EXPECT_EQ(texture.path_average(Vec2f(0.3f, 0.6f), Vec2f(0.3f, 0.6f)),
            texture.sample(Vec2f(0.3f, 0.6f)));
}

}  // namespace
}  // namespace kinray
