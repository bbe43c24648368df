// Lights and shadows: analytic shadow outlines (a quad above a plane), Embree's occlusion rays and
// the kinetic backend's shadow tracer against brute force on the built-in scenes, the diff's
// classification of shadow-mask disagreements, and camera-space lights.
#include <gtest/gtest.h>

#include <cmath>

#include "renderer/backends/backend.h"
#include "renderer/job/render_job.h"
#include "renderer/shadows/brute_force_shadow_tracer.h"
#include "renderer/shadows/lighting.h"
#include "renderer/shadows/shadow_rays.h"
#include "scenes/camera_space_lights.h"
#include "scenes/procedural.h"
#include "tests/address_sanitizer.h"
#include "tools/cli/light_flag.h"
#include "verification/image_diff.h"

namespace kinray {
namespace {

constexpr int kSize = 64;
constexpr uint32_t kGround = 0, kOccluder = 1;

/// A horizontal quad y = height over [x0, x1] x [z0, z1] (world space), facing up.
Object quad(const std::string& name, double height, double x0, double x1, double z0, double z1) {
  Object object;
  object.name = name;
  object.triangles = {{0, 1, 2}, {0, 2, 3}};
  object.key_times = {0.0};
  object.key_positions = {
      {Vec3(x0, height, z0), Vec3(x0, height, z1), Vec3(x1, height, z1), Vec3(x1, height, z0)}};
  return object;
}

/// Ground y = -1 and a quad at y = -0.5 over [-0.5, 0.5] x [-3.5, -2.5], seen by a 90 degree
/// camera at the origin looking down -z (so camera space is world space with z flipped).
Scene quad_over_plane(std::vector<Light> lights, double occluder_x1 = 0.5) {
  Scene scene;
  scene.name = "quad-over-plane";
  scene.objects = {quad("ground", -1.0, -6, 6, -12, -0.5),
                   quad("occluder", -0.5, -0.5, occluder_x1, -3.5, -2.5)};
  scene.camera.keys = {CameraKey{}};
  scene.camera.keys[0].fov_y_degrees = 90;
  scene.lights = std::move(lights);
  scene.validate("quad-over-plane");
  return scene;
}

/// The world point where pixel (i, j)'s ray meets the ground y = -1, or nullopt above the horizon.
std::optional<Vec3> ground_point(int i, int j) {
  const PixelRays image{kSize, kSize};
  const double x = image.x(i), y = image.y(j);
  if (!(y < 0)) return std::nullopt;
  const double s = -1.0 / y;
  return Vec3(x * s, -1.0, -s);
}

/// Renders frame 0 of `scene` with `backend` (kinetic backends trace shadows by brute force) and
/// shades it with `tracer`, or with the backend's own tracer when `tracer` is null.
Frame render_lit(const Scene& scene, const CameraSpaceScene& cs, const std::string& backend_name,
                 ShadowTracer* tracer = nullptr) {
  BackendConfig config;
  config.width = config.height = kSize;
  config.threads = 2;
  config.shadow_tree = ShadowTree::brute;
  std::unique_ptr<Backend> backend = make_backend(backend_name, cs, config);
  Frame frame;
  backend->render(0.0, frame);
  ShadowTracer* used = tracer ? tracer : backend->shadow_tracer();
  EXPECT_NE(used, nullptr);
  shade_frame_lit(cs, CameraSpaceLights(scene), *used, frame, 2);
  return frame;
}

/// Checks every ground pixel's mask against the exact shadow outline `shadowed` (pixels within
/// 1e-9 of the outline skipped) and that the occluder's top is lit; returns the shadowed count.
template <class Shadowed>
int check_outline(const Frame& frame, Shadowed shadowed) {
  int in_shadow = 0, checked = 0;
  for (int j = 0; j < kSize; ++j)
    for (int i = 0; i < kSize; ++i) {
      const size_t p = frame.index(i, j);
      if (frame.object[p] == kOccluder) {
        EXPECT_EQ(frame.lit[p], 1u) << "occluder pixel " << i << "," << j;
        continue;
      }
      if (frame.object[p] != kGround) continue;
      const std::optional<Vec3> point = ground_point(i, j);
      if (!point) {
        ADD_FAILURE() << "ground seen above the horizon";
        continue;
      }
      const std::optional<bool> expected = shadowed(*point);
      if (!expected) continue;
      ++checked;
      in_shadow += *expected;
      EXPECT_EQ(frame.lit[p], *expected ? 0u : 1u)
          << "ground pixel " << i << "," << j << " at " << point->transpose();
    }
  EXPECT_GT(checked, kSize * kSize / 4);
  return in_shadow;
}

/// Inside (true), outside (false) or within 1e-9 of (nullopt) the square |x - cx|, |z - cz| < h.
std::optional<bool> in_square(const Vec3& p, double cx, double cz, double h) {
  const double margin = std::max(std::abs(p.x() - cx), std::abs(p.z() - cz)) - h;
  if (std::abs(margin) < 1e-9) return std::nullopt;
  return margin < 0;
}

TEST(Shadows, PointLightCastsTheProjectedQuad) {
  // A light at (0, 1, -3): the quad at height -0.5 (1.5 below it) projects onto the ground (2
  // below it) scaled by 4/3 about the light's foot: the square |x| < 2/3, |z + 3| < 2/3.
  Light light;
  light.position = Vec3(0, 1, -3);
  const Scene scene = quad_over_plane({light});
  const CameraSpaceScene cs = CameraSpaceScene::build(scene);
  const auto shadowed = [](const Vec3& p) { return in_square(p, 0, -3, 2.0 / 3.0); };
  for (const char* backend : {"embree", "kinetic"}) {
    SCOPED_TRACE(backend);
    const Frame frame = render_lit(scene, cs, backend);
    EXPECT_GT(check_outline(frame, shadowed), 20);
  }
  BruteForceShadowTracer brute(cs);
  EXPECT_GT(check_outline(render_lit(scene, cs, "embree", &brute), shadowed), 20);
}

TEST(Shadows, DirectionalLightCastsTheQuadStraightDown) {
  Light light;
  light.kind = Light::Kind::directional;
  light.direction = Vec3(0, -1, 0);
  const Scene scene = quad_over_plane({light});
  const CameraSpaceScene cs = CameraSpaceScene::build(scene);
  const auto shadowed = [](const Vec3& p) { return in_square(p, 0, -3, 0.5); };
  for (const char* backend : {"embree", "kinetic"}) {
    SCOPED_TRACE(backend);
    EXPECT_GT(check_outline(render_lit(scene, cs, backend), shadowed), 10);
  }
}

TEST(Shadows, LightBehindTheSurfaceDoesNotReachIt) {
  // A light under the ground lights nothing the camera sees of it, and the lit colour is then
  // the ambient share of the base colour.
  Light below;
  below.position = Vec3(0, -3, -3);
  const Scene scene = quad_over_plane({below});
  const CameraSpaceScene cs = CameraSpaceScene::build(scene);
  const Frame frame = render_lit(scene, cs, "embree");
  const Color base = scene.materials[0].base_color;
  for (size_t p = 0; p < frame.pixel_count(); ++p) {
    if (frame.object[p] == kNoHit) continue;
    EXPECT_EQ(frame.lit[p], 0u);
    EXPECT_TRUE(frame.color[p].isApprox(base * 0.15f)) << frame.color[p].transpose();
  }
}

// Motion blur with lights cuts its intervals where a light's Lambert term turns (lit_side_mask):
// clearing a light whose term is not positive must shade exactly as before, and on a curved
// surface with smooth normals some lights face the triangle but not its normal.
TEST(Shadows, ALightWhoseLambertTermIsNotPositiveAddsNothing) {
  Scene scene = make_builtin_scene("wavy-sphere", {{"triangles", 2000}});
  Light point, sun;
  point.position = Vec3(2, 3, 4);
  sun.kind = Light::Kind::directional;
  sun.direction = Vec3(1, -1, -1).normalized();
  scene.lights = {point, sun};
  const CameraSpaceScene cs = CameraSpaceScene::build(scene);
  const Frame frame = render_lit(scene, cs, "embree");
  const std::vector<CameraSpaceLight> lights = CameraSpaceLights(scene).at(0.0);
  const PixelRays image{kSize, kSize};
  int facing_only = 0, seen = 0;
  for (int j = 0; j < kSize; ++j)
    for (int i = 0; i < kSize; ++i) {
      const size_t p = frame.index(i, j);
      if (frame.object[p] == kNoHit) continue;
      ++seen;
      const LitHit hit = lit_hit(cs, frame.object[p], frame.prim[p], image.direction(i, j), 0.0);
      const uint32_t side = lit_side_mask(hit, lights);
      for (uint32_t mask = 0; mask < 4; ++mask)
        ASSERT_EQ(lit_color(hit, lights, mask), lit_color(hit, lights, mask & side))
            << "pixel " << i << ", " << j << " mask " << mask;
      for (size_t l = 0; l < lights.size(); ++l)
        facing_only += shadow_ray(hit, lights[l], frame.object[p], frame.prim[p]).has_value() &&
                       (side >> l & 1u) == 0;
    }
  EXPECT_GT(seen, 500);
  EXPECT_GT(facing_only, 0) << "a light faces a triangle beyond its smooth normal's terminator";
}

TEST(Shadows, TwoLightsAreRecordedBitByBit) {
  Light left, right;
  left.position = Vec3(-2, 1, -3);
  right.position = Vec3(2, 1, -3);
  const Scene scene = quad_over_plane({left, right});
  const CameraSpaceScene cs = CameraSpaceScene::build(scene);
  const Frame frame = render_lit(scene, cs, "embree");
  int only_left = 0, only_right = 0;
  for (size_t p = 0; p < frame.pixel_count(); ++p) {
    if (frame.object[p] != kGround) continue;
    only_left += frame.lit[p] == 1u;
    only_right += frame.lit[p] == 2u;
  }
  // Each light's shadow falls on the other side, where only the other light reaches.
  EXPECT_GT(only_left, 10);
  EXPECT_GT(only_right, 10);
}

TEST(Shadows, EmbreeSkipsOnlyTheTriangleTheRayLeavesFrom) {
  // A ray that passes through the occluder's interior is blocked unless it names that triangle.
  const Scene scene = quad_over_plane({Light{}});
  const CameraSpaceScene cs = CameraSpaceScene::build(scene);
  BackendConfig config;
  config.width = config.height = 8;
  std::unique_ptr<Backend> embree = make_backend("embree", cs, config);
  Frame frame;
  embree->render(0.0, frame);
  ShadowTracer& tracer = *embree->shadow_tracer();
  tracer.advance_to(0.0);
  BruteForceShadowTracer brute(cs);
  brute.advance_to(0.0);
  // Camera space: the occluder's first triangle covers (x, z) near (-0.3, 2.9) at y = -0.5.
  ShadowRay ray;
  ray.origin = Vec3(-0.3, -0.9, 2.9);
  ray.direction = Vec3(0, 1, 0);
  ray.s_max = 1.0;
  std::vector<ShadowRay> rays(3, ray);
  rays[1].object = kOccluder;
  rays[1].prim = 0;
  rays[2].s_max = 0.3;  // stops short of the quad
  for (const ShadowTracer* t :
       {static_cast<const ShadowTracer*>(&tracer), static_cast<const ShadowTracer*>(&brute)}) {
    std::vector<uint8_t> blocked(3, 7);
    t->occluded(rays, blocked);
    EXPECT_EQ(blocked, (std::vector<uint8_t>{1, 0, 0})) << t->name();
  }
}

TEST(Shadows, DiffCallsAFlippedRobustBitRealAndAGrazingOneATie) {
  // Directional light straight down; the occluder's right edge is put exactly above the ground
  // point of pixel (i, j), so that pixel's shadow ray passes through the edge.
  const int i = 36, j = 42;
  const Vec3 graze = *ground_point(i, j);
  Light down;
  down.kind = Light::Kind::directional;
  down.direction = Vec3(0, -1, 0);
  const Scene scene = quad_over_plane({down}, graze.x());
  ASSERT_GT(graze.z(), -3.5);
  ASSERT_LT(graze.z(), -2.5);
  const CameraSpaceScene cs = CameraSpaceScene::build(scene);
  const Frame reference = render_lit(scene, cs, "embree");
  FrameComparator comparator(cs);
  EXPECT_EQ(comparator.compare(reference, reference).mismatch_real, 0u);

  Frame tested = reference;
  const size_t on_edge = reference.index(i, j);
  ASSERT_EQ(reference.object[on_edge], kGround);
  tested.lit[on_edge] ^= 1u;
  // A ground pixel well inside the shadow and one well outside it.
  size_t inside = SIZE_MAX, outside = SIZE_MAX;
  for (int jj = 0; jj < kSize; ++jj)
    for (int ii = 0; ii < kSize; ++ii) {
      const size_t p = reference.index(ii, jj);
      if (reference.object[p] != kGround) continue;
      const Vec3 g = *ground_point(ii, jj);
      const double dx = std::max(g.x() - graze.x(), -0.5 - g.x()), dz = std::abs(g.z() + 3) - 0.5;
      if (std::max(dx, dz) < -0.05) inside = p;
      if (std::max(dx, dz) > 0.05) outside = p;
    }
  ASSERT_NE(inside, SIZE_MAX);
  ASSERT_NE(outside, SIZE_MAX);
  tested.lit[inside] ^= 1u;
  tested.lit[outside] ^= 1u;
  const FrameDiff diff = comparator.compare(tested, reference);
  EXPECT_EQ(diff.pixels[on_edge], PixelClass::kTie);
  EXPECT_EQ(diff.pixels[inside], PixelClass::kReal);
  EXPECT_EQ(diff.pixels[outside], PixelClass::kReal);
  ASSERT_EQ(diff.shadow_lights.size(), 1u);
  EXPECT_EQ(diff.shadow_lights[0].real, 2u);
  EXPECT_EQ(diff.shadow_lights[0].tie, 1u);
  EXPECT_EQ(diff.mismatch_real, 2u);
  EXPECT_EQ(diff.mismatch_tie, 1u);
}

TEST(Shadows, CameraSpaceLightsMoveExactlyAsStaticVertices) {
  // A light at a static vertex stays on it in camera space at every time, camera animated.
  Scene scene = quad_over_plane({});
  scene.camera.keys = {Camera::look_at(0.0, Vec3(0, 0.5, 1), Vec3(0, -1, -3), Vec3::UnitY(), 60),
                       Camera::look_at(0.7, Vec3(2, 1.5, 0), Vec3(0, -1, -3), Vec3::UnitY(), 40),
                       Camera::look_at(1.0, Vec3(-1, 2, -1), Vec3(0, -1, -2), Vec3::UnitY(), 75)};
  Light light;
  light.position = scene.objects[1].key_positions[0][2];
  scene.lights = {light};
  const CameraSpaceScene cs = CameraSpaceScene::build(scene);
  const CameraSpaceLights lights(scene);
  for (double t : {0.0, 0.2, 0.7, 0.93, 1.0}) {
    const std::vector<CameraSpaceLight> at = lights.at(t);
    ASSERT_EQ(at.size(), 1u);
    EXPECT_EQ(at[0].position, cs.objects[1].position(2, t)) << "t = " << t;
  }
}

/// Renders `spec` with a point light and a directional light at 48x48 (32x32 under ASan), 2 frames,
/// with Embree (occlusion rays) and the kinetic backend (its default, the kinetic AABB tree), and
/// compares both the masks of the two and Embree's against brute force on Embree's own primary
/// hits.
void expect_masks_agree(const std::string& spec) {
  SCOPED_TRACE(spec);
  RenderParams params;
  params.scene = spec;
  // Fewer pixels under AddressSanitizer, where the brute force of every shadow ray is the slowest
  // part of the suite.
  params.width = params.height = test::kUnderAddressSanitizer ? 32 : 48;
  params.frames = 2;
  params.threads = 2;
  params.lights = {parse_light_flag("point:2,5,-3"), parse_light_flag("dir:-1,-2,0.5:0.5,0.6,0.7")};
  RenderJob job(params);
  std::unique_ptr<Backend> embree = job.make_backend("embree");
  std::unique_ptr<Backend> kinetic = job.make_backend("kinetic");
  FrameComparator comparator(job.camera_space());
  BruteForceShadowTracer brute(job.camera_space());
  const CameraSpaceLights lights(job.scene());
  size_t shadowed = 0;
  for (size_t f = 0; f < job.frame_times().size(); ++f) {
    Frame a, b;
    job.render_frame(*embree, f, a);
    job.render_frame(*kinetic, f, b);
    const FrameDiff diff = comparator.compare(b, a);
    EXPECT_EQ(diff.mismatch_real, 0u) << "frame " << f;
    ASSERT_EQ(diff.shadow_lights.size(), 2u);
    Frame c = a;
    shade_frame_lit(job.camera_space(), lights, brute, c, 2);
    const FrameDiff exact = comparator.compare(a, c);
    EXPECT_EQ(exact.mismatch_real, 0u) << "frame " << f;
    for (size_t p = 0; p < a.pixel_count(); ++p)
      shadowed += a.object[p] != kNoHit && a.lit[p] != 3u;
  }
  EXPECT_GT(shadowed, 0u);
}

TEST(Shadows, EmbreeAndKineticMasksAgreeOnBuiltInScenes) {
  for (const char* spec : {"wavy-sphere:triangles=3000", "cloth:triangles=2000", "orbit",
                           "flythrough", "static-moving"})
    expect_masks_agree(spec);
}

#ifdef KINRAY_WITH_OSMESA
TEST(Shadows, OsmesaBorrowsEmbreesOcclusionRays) {
  RenderParams params;
  params.scene = "static-moving:triangles=2000";
  params.width = params.height = 32;
  params.frames = 1;
  params.lights = {parse_light_flag("point:2,5,-3")};
  RenderJob job(params);
  std::unique_ptr<Backend> osmesa = job.make_backend("osmesa");
  std::unique_ptr<Backend> embree = job.make_backend("embree");
  Frame a, b;
  job.render_frame(*osmesa, 0, a);
  job.render_frame(*embree, 0, b);
  ASSERT_EQ(a.lit.size(), a.pixel_count());
  FrameComparator comparator(job.camera_space());
  const FrameDiff diff = comparator.compare(a, b);
  ASSERT_EQ(diff.shadow_lights.size(), 1u);
  EXPECT_EQ(diff.shadow_lights[0].real, 0u);
}
#endif

TEST(Shadows, NoLightsMeansNoMaskAndTheHeadlight) {
  RenderParams params;
  params.scene = "static-moving";
  params.width = params.height = 16;
  params.frames = 1;
  RenderJob job(params);
  std::unique_ptr<Backend> embree = job.make_backend("embree");
  EXPECT_EQ(embree->shadow_tracer(), nullptr);
  Frame frame;
  job.render_frame(*embree, 0, frame);
  EXPECT_TRUE(frame.lit.empty());
}

}  // namespace
}  // namespace kinray
