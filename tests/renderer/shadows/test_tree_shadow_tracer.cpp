// Shadow rays through the kinetic AABB tree, the kinetic BoxTree and the bottom-up tree
// (renderer/shadows/tree_shadow_tracer.h) against a brute-force occlusion test and against Embree, on
// every built-in scene at several frame times, kinetic trees audited.
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <random>

#include "renderer/shadows/embree_shadow_tracer.h"
#include "renderer/shadows/tree_shadow_tracer.h"
#include "scenes/camera_space.h"
#include "scenes/procedural.h"
#include "scenes/scene_loader.h"
#include "tests/scenes/model_test_support.h"

namespace kinray {
namespace {

enum class Verdict { blocked, clear, tie };

/// Brute force, written apart from the trees' test: every present triangle but the ray's own, by
/// the plane of the triangle and the signs of its barycentric coordinates. A hit within `margin`
/// (relative) of an edge, of the ray's origin or of the light is a tie.
Verdict brute_force(const CameraSpaceScene& cs, const ShadowRay& ray, double t, double margin) {
  bool tie = false;
  for (size_t o = 0; o < cs.objects.size(); ++o) {
    const CameraSpaceObject& obj = cs.objects[o];
    if (!obj.visible(t)) continue;
    const auto& tris = cs.triangles(o);
    for (uint32_t k = 0; k < tris.size(); ++k) {
      if (obj.object == ray.object && k == ray.prim) continue;
      const Vec3 a = obj.position(tris[k][0], t), b = obj.position(tris[k][1], t),
                 c = obj.position(tris[k][2], t);
      const Vec3 n = (b - a).cross(c - a);
      const double denom = n.dot(ray.direction);
      if (denom == 0) continue;
      const double s = n.dot(a - ray.origin) / denom;
      const Vec3 p = ray.origin + s * ray.direction;
      const double area = n.squaredNorm();
      const double w0 = (c - b).cross(p - b).dot(n) / area, w1 = (a - c).cross(p - c).dot(n) / area,
                   w2 = (b - a).cross(p - a).dot(n) / area;
      const double wmin = std::min({w0, w1, w2});
      const double s_hi = std::isfinite(ray.s_max) ? ray.s_max : kInfinity;
      if (wmin > margin && s > margin && s < s_hi * (1 - margin)) return Verdict::blocked;
      if (wmin >= -margin && s >= -margin && s <= s_hi * (1 + margin)) tie = true;
    }
  }
  return tie ? Verdict::tie : Verdict::clear;
}

/// Shadow rays from random points of random present triangles to a point light and along a
/// directional light.
std::vector<ShadowRay> random_shadow_rays(const CameraSpaceScene& cs, double t, std::mt19937& rng,
                                          int count) {
  std::vector<ShadowRay> rays;
  std::uniform_real_distribution<double> u(0, 1);
  const Vec3 light(1.5, 2.5, -0.5);
  while (int(rays.size()) < count) {
    const size_t o = rng() % cs.objects.size();
    const CameraSpaceObject& obj = cs.objects[o];
    const auto& tris = cs.triangles(o);
    if (!obj.visible(t) || tris.empty()) continue;
    const auto k = uint32_t(rng() % tris.size());
    double b1 = u(rng), b2 = u(rng);
    if (b1 + b2 > 1) b1 = 1 - b1, b2 = 1 - b2;
    const Vec3 a = obj.position(tris[k][0], t), b = obj.position(tris[k][1], t),
               c = obj.position(tris[k][2], t);
    ShadowRay r;
    r.origin = a + b1 * (b - a) + b2 * (c - a);
    r.object = obj.object;
    r.prim = k;
    if (rays.size() % 2 == 0) {
      r.direction = light - r.origin;
      r.s_max = 1;
    } else {
      r.direction = Vec3(-0.3, 1.0, 0.2);
    }
    rays.push_back(r);
  }
  return rays;
}

/// Every tree against the brute force and Embree against the brute force, at six times of the
/// shot; the kinetic trees audited.
void check_scene(const Scene& scene, std::mt19937& rng, size_t min_blocked = 10) {
  const CameraSpaceScene cs = CameraSpaceScene::build(scene);
  std::vector<std::unique_ptr<ShadowTracer>> tracers;
  tracers.push_back(make_tree_shadow_tracer(cs, ShadowTree::aabb, true));
  tracers.push_back(make_tree_shadow_tracer(cs, ShadowTree::boxtree, true));
  tracers.push_back(make_tree_shadow_tracer(cs, ShadowTree::refit, false));
  auto embree = std::make_unique<EmbreeShadowTracer>(cs, EmbreeShadowTracer::Update::kRefit);
  size_t blocked_rays = 0, clear_rays = 0, embree_real = 0;
  const std::vector<double> keys = scene.key_times();
  const double t0 = keys.front(), t1 = keys.back();
  for (double f : {0.0, 0.13, 0.4, 0.41, 0.77, 1.0}) {
    const double t = t0 + f * (t1 - t0);
    embree->advance_to(t);
    for (auto& tracer : tracers) tracer->advance_to(t);
    const std::vector<ShadowRay> rays = random_shadow_rays(cs, t, rng, 150);
    std::vector<uint8_t> reference(rays.size()), result(rays.size());
    embree->occluded(rays, reference);
    std::vector<Verdict> exact(rays.size());  // each ray's brute force, once for every tracer
    for (size_t i = 0; i < rays.size(); ++i) {
      const Verdict v = exact[i] = brute_force(cs, rays[i], t, 1e-9);
      blocked_rays += v == Verdict::blocked;
      clear_rays += v == Verdict::clear;
      const Verdict loose = brute_force(cs, rays[i], t, 1e-5);  // Embree traces in float
      if (loose != Verdict::tie && reference[i] != (loose == Verdict::blocked)) ++embree_real;
    }
    for (auto& tracer : tracers) {
      tracer->occluded(rays, result);
      for (size_t i = 0; i < rays.size(); ++i) {
        const Verdict v = exact[i];
        if (v != Verdict::tie) {
          EXPECT_EQ(result[i], v == Verdict::blocked ? 1 : 0)
              << tracer->name() << " ray " << i << " t " << t;
        }
      }
    }
  }
  EXPECT_EQ(embree_real, 0u);  // the test's brute force is right, as Embree sees it
  EXPECT_GE(blocked_rays, min_blocked);
  EXPECT_GT(clear_rays, 10u);
  nlohmann::json stats;
  tracers[0]->write_stats(stats);
  EXPECT_EQ(stats["shadow_tree"]["kind"], "aabb");
  for (const char* key : {"total", "leaf", "tree", "flightplan", "insert", "delete"})
    EXPECT_TRUE(stats["shadow_tree"]["events"].contains(key)) << key;
  for (const char* key : {"compactness", "responsiveness", "locality", "efficiency"})
    EXPECT_TRUE(stats["shadow_tree"]["quality"].contains(key)) << key;
  // The keys' share of the tree's time: part of its build and updates.
  const nlohmann::json& time = stats["shadow_tree"]["time_s"];
  EXPECT_GE(time["mesh_events"].get<double>(), 0.0);
  EXPECT_LE(time["mesh_events"].get<double>(),
            time["build"].get<double>() + time["update"].get<double>());
}

TEST(TreeShadowTracer, MatchesBruteForceAndEmbreeOnBuiltinScenes) {
  std::mt19937 rng(2024);
  for (const BuiltinScene& builtin : builtin_scenes()) {
    SCOPED_TRACE(builtin.name);
    check_scene(
        make_builtin_scene(builtin.name, {{"triangles", 1500}, {"duration", 1}, {"keyrate", 6}}),
        rng);
  }
}

TEST(TreeShadowTracer, MatchesBruteForceAndEmbreeOnAnimatedModels) {
  std::mt19937 rng(7);
  // A closed morphing sphere shadows itself; simple_skin (8 triangles bending) never does.
  const std::pair<std::filesystem::path, size_t> models[] = {
      {testing::kSharedModels / "glTF2/AnimatedMorphSphere/glTF/AnimatedMorphSphere.gltf", 10},
      {testing::kTestModels / "glTF2/simple_skin/simple_skin.gltf", 0}};
  for (const auto& [model, min_blocked] : models) {
    SCOPED_TRACE(model.string());
    ASSERT_TRUE(std::filesystem::exists(model));
    check_scene(load_scene(model.string()), rng, min_blocked);
  }
}

TEST(TreeShadowTracer, BruteIsNotATree) {
  const Scene scene = make_builtin_scene("wavy-sphere", {{"triangles", 100}});
  const CameraSpaceScene cs = CameraSpaceScene::build(scene);
  EXPECT_THROW((void)make_tree_shadow_tracer(cs, ShadowTree::brute, false), std::invalid_argument);
}

}  // namespace
}  // namespace kinray
