// Shading split into a triangle's part at an instant and each ray's part (motion blur builds the
// first once per front and quadrature node): the same colour, bit for bit, as the whole
// computation per pixel, written out here as it was before the split.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <random>

#include "renderer/backends/backend.h"
#include "renderer/shadows/lighting.h"
#include "renderer/shading.h"
#include "scenes/camera_space.h"
#include "scenes/camera_space_lights.h"
#include "scenes/model_import.h"
#include "scenes/procedural.h"

namespace kinray {
namespace {

namespace fs = std::filesystem;

/// Moller-Trumbore barycentrics, the interpolated normal and the headlight Lambert term, in one
/// piece on (object, prim) at t: the reference.
Color headlight_reference(const CameraSpaceScene& scene, const PixelRays& image, int i, int j,
                          uint32_t object, uint32_t prim, double t) {
  const KeySegment at = locate(scene.objects[object].key_times, t);
  const CameraSpaceObject& cs = scene.objects[object];
  const Object& source = scene.scene->objects[object];
  const Triangle& tri = source.triangles[prim];
  const Vec3 d = image.direction(i, j);
  const Vec3 p0 = cs.position(tri[0], at), p1 = cs.position(tri[1], at),
             p2 = cs.position(tri[2], at);
  const Vec3 e1 = p1 - p0, e2 = p2 - p0;
  const Vec3 pvec = d.cross(e2);
  const double det = e1.dot(pvec);
  double u = 1.0 / 3.0, v = 1.0 / 3.0;
  if (std::abs(det) > 0) {
    const Vec3 tvec = -p0;
    const Vec3 qvec = tvec.cross(e1);
    u = std::clamp(tvec.dot(pvec) / det, 0.0, 1.0);
    v = std::clamp(d.dot(qvec) / det, 0.0, 1.0 - u);
  }
  const float w0 = float(1.0 - u - v), w1 = float(u), w2 = float(v);
  Eigen::Vector3f n =
      w0 * cs.normal(tri[0], at) + w1 * cs.normal(tri[1], at) + w2 * cs.normal(tri[2], at);
  const float length = n.norm();
  const Eigen::Vector3f normal =
      length > 0 ? Eigen::Vector3f(n / length) : Eigen::Vector3f(0, 0, -1);
  const Eigen::Vector3f view = unfold(d, scene.tan_half_fov(t)).normalized().cast<float>();
  const Material& material = scene.scene->materials[source.material];
  Color base = material.base_color;
  if (material.texture >= 0 && !source.uvs.empty()) {
    const Vec2f uv = w0 * source.uvs[tri[0]] + w1 * source.uvs[tri[1]] + w2 * source.uvs[tri[2]];
    base = base.cwiseProduct(scene.scene->textures[size_t(material.texture)].sample(uv));
  }
  return base * (kAmbient + kDiffuse * std::abs(normal.dot(view)));
}

bool same_bits(const Color& a, const Color& b) {
  return std::memcmp(a.data(), b.data(), sizeof(float) * 3) == 0;
}

void check_scene(const Scene& scene, int checks) {
  const CameraSpaceScene cs = CameraSpaceScene::build(scene);
  const PixelRays image{64, 48};
  std::mt19937 rng(7);
  const auto [first, last] = std::pair{scene.key_times().front(), scene.key_times().back()};
  int checked = 0;
  for (int k = 0; k < checks; ++k) {
    const uint32_t object = uint32_t(rng() % cs.objects.size());
    const auto& triangles = scene.objects[object].triangles;
    if (triangles.empty()) continue;
    const uint32_t prim = uint32_t(rng() % triangles.size());
    const int i = int(rng() % 64), j = int(rng() % 48);
    const double t = first + (last - first) * std::uniform_real_distribution<double>(0, 1)(rng);
    const Color expected = headlight_reference(cs, image, i, j, object, prim, t);
    ASSERT_TRUE(same_bits(shade_hit(cs, image, i, j, object, prim, t), expected))
        << "object " << object << " prim " << prim << " pixel " << i << "," << j << " t " << t;
    const ShadingInstant instant = shading_instant(cs, object, t);
    const TriangleAtInstant triangle = triangle_at_instant(cs, object, prim, instant);
    const Vec3 d = image.direction(i, j);
    const Eigen::Vector3f view = view_direction(d, instant.tan_half_fov);
    ASSERT_TRUE(same_bits(headlight_color(triangle, d, view), expected));
    const SurfacePoint surface = surface_point(triangle, d, view);
    ASSERT_TRUE(same_bits(headlight_color(surface), expected));
    EXPECT_EQ(surface.p1, cs.objects[object].position(triangles[prim][1], instant.segment));
    ++checked;
  }
  EXPECT_GT(checked, checks / 2);
}

TEST(Shading, ATriangleAtAnInstantShadesEveryRayAsTheWholeComputation) {
  check_scene(make_builtin_scene("wavy-sphere", {{"triangles", 2000}}), 2000);
  check_scene(make_builtin_scene("orbit"), 2000);
  const fs::path skinned = "/usr/share/assimp/models/X/Testwuson.X";
  const fs::path textured = "/usr/share/assimp/models/glTF2/BoxTextured-glTF/BoxTextured.gltf";
  for (const fs::path& path : {skinned, textured}) {
    if (!fs::exists(path)) GTEST_SKIP() << path << " is not installed";
    check_scene(load_model(path.string()), 2000);
  }
}

/// shade_frame on a frame whose hits come in runs (of a triangle, of an object, of background)
/// of random lengths, at a random time: every pixel is the reference's colour bit for bit.
void check_frame(const Scene& scene, uint32_t seed) {
  const CameraSpaceScene cs = CameraSpaceScene::build(scene);
  std::mt19937 rng(seed);
  Frame frame;
  frame.resize(64, 48);
  const auto [first, last] = std::pair{scene.key_times().front(), scene.key_times().back()};
  frame.time = first + (last - first) * std::uniform_real_distribution<double>(0, 1)(rng);
  uint32_t object = 0, prim = 0;
  for (size_t p = 0; p < frame.pixel_count();) {
    const size_t run = 1 + rng() % 6;
    const uint32_t pick = uint32_t(rng() % 8);
    if (pick == 0 || scene.objects[object].triangles.empty()) {
      object = uint32_t(rng() % cs.objects.size());
      prim = 0;
    }
    const auto& triangles = scene.objects[object].triangles;
    const bool background = pick == 1 || triangles.empty();
    if (!triangles.empty()) prim = uint32_t(rng() % triangles.size());
    for (size_t k = 0; k < run && p < frame.pixel_count(); ++k, ++p) {
      frame.object[p] = background ? kNoHit : object;
      frame.prim[p] = background ? kNoHit : prim;
    }
  }
  shade_frame(cs, frame, 2);
  const PixelRays image{frame.width, frame.height};
  for (int j = 0; j < frame.height; ++j)
    for (int i = 0; i < frame.width; ++i) {
      const size_t p = frame.index(i, j);
      const Color expected =
          frame.object[p] == kNoHit
              ? kBackgroundColor
              : headlight_reference(cs, image, i, j, frame.object[p], frame.prim[p], frame.time);
      ASSERT_TRUE(same_bits(frame.color[p], expected)) << "pixel " << i << "," << j;
    }
}

TEST(Shading, AFrameShadesEveryPixelAsTheWholeComputation) {
  for (uint32_t seed = 1; seed <= 4; ++seed) {
    check_frame(make_builtin_scene("wavy-sphere", {{"triangles", 2000}}), seed);
    check_frame(make_builtin_scene("orbit"), seed);
  }
  const fs::path textured = "/usr/share/assimp/models/glTF2/BoxTextured-glTF/BoxTextured.gltf";
  if (!fs::exists(textured)) GTEST_SKIP() << textured << " is not installed";
  check_frame(load_model(textured.string()), 5);
}

// Colours worked out by hand, not by a transcription of the shading: a square facing a camera
// with a 90 degree field of view, 2 units in front of it, so that pixel (i, j)'s ray runs along
// (x, y, -1) and meets the square's normal (0, 0, 1) at cos = 1 / sqrt(x^2 + y^2 + 1).
Scene facing_square(std::vector<Light> lights) {
  Scene scene;
  scene.name = "facing-square";
  Object square;
  square.name = "square";
  square.triangles = {{0, 1, 2}, {0, 2, 3}};
  square.key_times = {0.0};
  square.key_positions = {{Vec3(-4, -4, -2), Vec3(4, -4, -2), Vec3(4, 4, -2), Vec3(-4, 4, -2)}};
  scene.objects = {square};
  scene.materials = {Material{}};
  scene.materials[0].base_color = Color(0.5f, 0.4f, 0.2f);
  scene.camera.keys = {CameraKey{}};
  scene.camera.keys[0].fov_y_degrees = 90;
  scene.lights = std::move(lights);
  scene.validate("facing-square");
  return scene;
}

Frame render_square(const Scene& scene) {
  const CameraSpaceScene cs = CameraSpaceScene::build(scene);
  BackendConfig config;
  config.width = config.height = 64;
  config.threads = 1;
  std::unique_ptr<Backend> backend = make_backend("embree", cs, config);
  Frame frame;
  backend->render(0.0, frame);
  if (scene.lights.empty())
    shade_frame(cs, frame, 1);
  else
    shade_frame_lit(cs, CameraSpaceLights(scene), *backend->shadow_tracer(), frame, 1);
  return frame;
}

TEST(Shading, AFacingSquareUnderTheHeadlightIsItsColourTimesTheCosine) {
  const Scene scene = facing_square({});
  const Frame frame = render_square(scene);
  const PixelRays image{64, 64};
  const Color base(0.5f, 0.4f, 0.2f);
  int checked = 0;
  for (const auto& [i, j] : {std::pair{32, 32}, {31, 31}, {0, 0}, {63, 10}, {5, 50}}) {
    const size_t p = frame.index(i, j);
    ASSERT_EQ(frame.object[p], 0u);
    const double x = image.x(i), y = image.y(j);
    const double cosine = 1 / std::sqrt(x * x + y * y + 1);  // the view ray against the normal
    const Color expected = base * float(0.15 + 0.85 * cosine);
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(frame.color[p][c], expected[c], 1e-5) << "pixel " << i << "," << j;
    ++checked;
  }
  // at the image's centre the ray meets the square head on: the full base colour
  const size_t centre = frame.index(32, 32);
  EXPECT_NEAR(frame.color[centre][0], 0.5f, 2e-3);
  EXPECT_EQ(checked, 5);
}

TEST(Shading, ALightAtSixtyDegreesGivesHalfItsDiffuseShare) {
  // A directional light travelling along (0, -sin 60, -cos 60): towards the light is
  // (0, sin 60, cos 60), 60 degrees from the normal, so every pixel of the square receives
  // ambient + diffuse * cos 60 = 0.15 + 0.85 / 2 = 0.575 of its base colour. A light of
  // colour (1, 0.5, 0) scales the diffuse share per channel.
  const double angle = 60 * M_PI / 180;
  Light light;
  light.kind = Light::Kind::directional;
  light.direction = Vec3(0, -std::sin(angle), -std::cos(angle));
  for (const auto& [colour, factor] :
       {std::pair{Color(1, 1, 1), Color(0.575f, 0.575f, 0.575f)},
        std::pair{Color(1, 0.5f, 0), Color(0.575f, 0.15f + 0.85f * 0.25f, 0.15f)}}) {
    light.color = colour;
    const Frame frame = render_square(facing_square({light}));
    // pixels off the square's diagonal: a pixel centre exactly on the edge two coplanar
    // triangles share starts its shadow ray on both, and the other one may block it
    for (const auto& [i, j] : {std::pair{32, 20}, {3, 50}, {60, 10}}) {
      const size_t p = frame.index(i, j);
      ASSERT_EQ(frame.object[p], 0u);
      EXPECT_EQ(frame.lit[p], 1u) << "nothing stands between the square and the light";
      const Color expected = Color(0.5f, 0.4f, 0.2f).cwiseProduct(factor);
      for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(frame.color[p][c], expected[c], 1e-5) << "pixel " << i << "," << j;
    }
  }
  // the same light from behind the square does not reach its visible side: ambient alone
  light.color = Color(1, 1, 1);
  light.direction = -light.direction;
  const Frame behind = render_square(facing_square({light}));
  const size_t p = behind.index(32, 20);
  for (int c = 0; c < 3; ++c)
    EXPECT_NEAR(behind.color[p][c], Color(0.5f, 0.4f, 0.2f)[c] * 0.15f, 1e-5);
}

}  // namespace
}  // namespace kinray
