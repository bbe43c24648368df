// The OSMesa reference backend on scenes whose ID and depth buffers are known exactly.
#ifdef KINRAY_WITH_OSMESA

#include <gtest/gtest.h>

#include <cmath>

#include "renderer/backends/embree_backend.h"
#include "renderer/backends/id_rasterizer.h"
#include "renderer/backends/osmesa_backend.h"
#include "renderer/shading.h"
#include "scenes/procedural.h"
#include "tests/renderer/analytic_scenes.h"
#include "util/input_error.h"
#include "verification/image_diff.h"

namespace kinray {
namespace {

using test::on_ray;

constexpr int kSize = 32;

// A quad over pixel columns [8, 24) and rows [2, 14) (the top half), tilted in depth: its corners
// lie on the rays through those pixel corners at depths 2, 3, 4 and 2.5. Prim 0 is the upper-right
// triangle (TL, TR, BR), prim 1 the lower-left (TL, BR, BL); no pixel centre lies on the diagonal
// (it would need 6i - 8j = 33).
Object tilted_quad() {
  const Vec3 tl = on_ray(8, 2, 2.0, kSize, kSize), tr = on_ray(24, 2, 3.0, kSize, kSize);
  const Vec3 br = on_ray(24, 14, 4.0, kSize, kSize), bl = on_ray(8, 14, 2.5, kSize, kSize);
  return test::camera_space_object("quad", {{0, 1, 2}, {0, 2, 3}}, {{tl, tr, br, bl}});
}

bool in_quad(int i, int j) {
  return i >= 8 && i < 24 && j >= 2 && j < 14;
}
uint32_t quad_prim(int i, int j) {
  const double u = i + 0.5, v = j + 0.5;
  return (v - 2) < (u - 8) * 12.0 / 16.0 ? 0u : 1u;
}

TEST(OsmesaBackend, QuadInTopHalfHasExactIdsAndDepths) {
  const Scene scene = test::analytic_scene({tilted_quad()});
  const CameraSpaceScene cs = CameraSpaceScene::build(scene);
  auto backend = make_osmesa_backend(cs, BackendConfig{.width = kSize, .height = kSize});
  EXPECT_EQ(backend->name(), "osmesa");
  Frame frame;
  backend->render(0.0, frame);
  ASSERT_EQ(frame.width, kSize);
  ASSERT_EQ(frame.height, kSize);
  const PixelRays image{kSize, kSize};
  const Triangle* triangles = scene.objects[0].triangles.data();
  for (int j = 0; j < kSize; ++j)
    for (int i = 0; i < kSize; ++i) {
      const size_t p = frame.index(i, j);
      if (!in_quad(i, j)) {
        EXPECT_EQ(frame.object[p], kNoHit) << i << "," << j;
        EXPECT_TRUE(std::isinf(frame.depth[p])) << i << "," << j;
        continue;
      }
      ASSERT_EQ(frame.object[p], 0u) << i << "," << j;
      ASSERT_EQ(frame.prim[p], quad_prim(i, j)) << i << "," << j;
      const Triangle& tri = triangles[frame.prim[p]];
      const double z =
          test::plane_depth(cs.objects[0].position(tri[0], 0), cs.objects[0].position(tri[1], 0),
                            cs.objects[0].position(tri[2], 0), image.direction(i, j));
      EXPECT_NEAR(frame.depth[p], z, 2e-6 * z) << i << "," << j;
    }
}

TEST(OsmesaBackend, NearerObjectWinsAndEveryObjectDecodes) {
  // Object 0: an empty mesh (it takes no ids); object 1: the quad; object 2: a big triangle at
  // depth 3 behind part of the quad and in front of the rest (the quad runs from depth 2 to 4).
  Object empty = test::camera_space_object("empty", {}, {{}});
  const Vec3 a = on_ray(0, 0, 3.0, kSize, kSize), b = on_ray(64, 0, 3.0, kSize, kSize);
  const Vec3 c = on_ray(0, 64, 3.0, kSize, kSize);
  Object wall = test::camera_space_object("wall", {{0, 1, 2}}, {{a, b, c}});
  const Scene scene = test::analytic_scene({empty, tilted_quad(), wall});
  const CameraSpaceScene cs = CameraSpaceScene::build(scene);
  auto backend = make_osmesa_backend(cs, BackendConfig{.width = kSize, .height = kSize});
  Frame frame;
  backend->render(0.0, frame);
  const PixelRays image{kSize, kSize};
  int quad_pixels = 0, wall_pixels = 0;
  for (int j = 0; j < kSize; ++j)
    for (int i = 0; i < kSize; ++i) {
      const size_t p = frame.index(i, j);
      ASSERT_NE(frame.object[p], 0u);
      bool quad_in_front = false;
      if (in_quad(i, j)) {
        const Triangle& tri = scene.objects[1].triangles[quad_prim(i, j)];
        const double z =
            test::plane_depth(cs.objects[1].position(tri[0], 0), cs.objects[1].position(tri[1], 0),
                              cs.objects[1].position(tri[2], 0), image.direction(i, j));
        // Pixels within a float ulp of the crossing could go either way; the test keeps away.
        if (std::abs(z - 3.0) < 1e-4) continue;
        quad_in_front = z < 3.0;
      }
      if (quad_in_front) {
        EXPECT_EQ(frame.object[p], 1u) << i << "," << j;
        EXPECT_EQ(frame.prim[p], quad_prim(i, j)) << i << "," << j;
        ++quad_pixels;
      } else {
        EXPECT_EQ(frame.object[p], 2u) << i << "," << j;
        EXPECT_EQ(frame.prim[p], 0u) << i << "," << j;
        EXPECT_NEAR(frame.depth[p], 3.0, 1e-6) << i << "," << j;
        ++wall_pixels;
      }
    }
  EXPECT_GT(quad_pixels, 40);
  EXPECT_GT(wall_pixels, 800);
}

TEST(OsmesaBackend, RendersTheMotionAtFrameTime) {
  // A square of 4 x 4 pixels sliding right by 16 pixels over [0, 1]: at t = 0.5 it covers columns
  // [10, 14) of rows [20, 24) (the bottom half), and it is visible only on [0, 0.75).
  auto square = [](double u0) {
    return std::vector<Vec3>{on_ray(u0, 20, 5, kSize, kSize), on_ray(u0 + 4, 20, 5, kSize, kSize),
                             on_ray(u0 + 4, 24, 5, kSize, kSize), on_ray(u0, 24, 5, kSize, kSize)};
  };
  Object object = test::camera_space_object("slider", {{0, 1, 2}, {0, 2, 3}},
                                            {square(2), square(18)}, {0.0, 1.0});
  object.disappear = 0.75;
  const Scene scene = test::analytic_scene({object});
  const CameraSpaceScene cs = CameraSpaceScene::build(scene);
  auto backend = make_osmesa_backend(cs, BackendConfig{.width = kSize, .height = kSize});
  Frame frame;
  backend->render(0.5, frame);
  EXPECT_EQ(frame.time, 0.5);
  for (int j = 0; j < kSize; ++j)
    for (int i = 0; i < kSize; ++i) {
      const bool inside = i >= 10 && i < 14 && j >= 20 && j < 24;
      EXPECT_EQ(frame.object[frame.index(i, j)] == 0u, inside) << i << "," << j;
    }
  backend->render(0.8, frame);
  for (uint32_t o : frame.object) EXPECT_EQ(o, kNoHit);
}

TEST(OsmesaBackend, TriangleCrossingTheEyePlaneIsClippedOnlyAtTheNearPlane) {
  // A floor y = -1 that runs from behind the eye (z = -4) to z = 8: the sign rule covers every
  // pixel whose ray goes down and meets the floor before z = 8; GL must agree away from its edges.
  Object floor = test::camera_space_object(
      "floor", {{0, 1, 2}, {0, 2, 3}},
      {{Vec3(-8, -1, -4), Vec3(8, -1, -4), Vec3(8, -1, 8), Vec3(-8, -1, 8)}});
  const Scene scene = test::analytic_scene({floor});
  const CameraSpaceScene cs = CameraSpaceScene::build(scene);
  auto backend = make_osmesa_backend(cs, BackendConfig{.width = kSize, .height = kSize});
  Frame frame;
  backend->render(0.0, frame);
  const PixelRays image{kSize, kSize};
  int covered = 0;
  for (int j = 0; j < kSize; ++j)
    for (int i = 0; i < kSize; ++i) {
      const Vec3 d = image.direction(i, j);
      if (d.y() >= 0) {
        EXPECT_EQ(frame.object[frame.index(i, j)], kNoHit);
        continue;
      }
      const double z = -1.0 / d.y();  // the ray meets y = -1 at depth z, at x = d.x * z
      const double x = d.x() * z;
      if (std::abs(z - 8) < 1e-3 || std::abs(std::abs(x) - 8) < 1e-3) continue;
      const bool hit = z < 8 && std::abs(x) < 8;
      EXPECT_EQ(frame.object[frame.index(i, j)] == 0u, hit) << i << "," << j;
      if (hit) {
        EXPECT_NEAR(frame.depth[frame.index(i, j)], z, 2e-6 * z);
        ++covered;
      }
    }
  EXPECT_GT(covered, 300);
}

TEST(OsmesaBackend, RasterizerReturnsAllFourIdBytesInImageOrder) {
  // Clip space directly: the top half (NDC y in [0, 1]) as two triangles whose ids use every byte.
  auto rasterizer = make_osmesa_rasterizer();
  const float near = 0.25f;
  const std::vector<Eigen::Vector4f> clip = {{-1, 0, near, 1}, {1, 0, near, 1}, {1, 1, near, 1},
                                             {-1, 0, near, 1}, {1, 1, near, 1}, {-1, 1, near, 1}};
  const std::vector<uint32_t> ids = {0xA1B2C3D4u, 0x01FF7F80u};
  RasterImage out;
  rasterizer->rasterize(RasterBatch{8, 6, clip, ids}, out);
  ASSERT_EQ(out.id.size(), 48u);
  for (int j = 0; j < 6; ++j)
    for (int i = 0; i < 8; ++i) {
      const uint32_t id = out.id[size_t(j) * 8 + size_t(i)];
      if (j >= 3) {
        EXPECT_EQ(id, 0u) << i << "," << j;
        EXPECT_EQ(out.depth[size_t(j) * 8 + size_t(i)], 0.0f);
        continue;
      }
      // Row j's centre is at NDC y = 1 - (2j + 1) / 6, column i's at x = (2i + 1) / 8 - 1; the
      // first triangle is below the diagonal y = (x + 1) / 2.
      const double x = (2 * i + 1) / 8.0 - 1, y = 1 - (2 * j + 1) / 6.0;
      EXPECT_EQ(id, y < (x + 1) / 2 ? ids[0] : ids[1]) << i << "," << j;
      EXPECT_EQ(out.depth[size_t(j) * 8 + size_t(i)], near);
    }
}

TEST(OsmesaBackend, TriangleIdsNumberEveryTriangleOfEveryObject) {
  const Vec3 a(0, 0, 1), b(1, 0, 1), c(0, 1, 1);
  Object one = test::camera_space_object("one", {{0, 1, 2}}, {{a, b, c}});
  Object none = test::camera_space_object("none", {}, {{}});
  Object three = test::camera_space_object("three", {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}}, {{a, b, c}});
  const Scene scene = test::analytic_scene({one, none, three});
  const CameraSpaceScene cs = CameraSpaceScene::build(scene);
  const TriangleIds ids(cs);
  EXPECT_EQ(ids.id(0, 0), 1u);
  EXPECT_EQ(ids.id(2, 0), 2u);
  EXPECT_EQ(ids.id(2, 2), 4u);
  uint32_t object = 0, prim = 0;
  ids.decode(1, object, prim);
  EXPECT_EQ(object, 0u);
  EXPECT_EQ(prim, 0u);
  ids.decode(3, object, prim);
  EXPECT_EQ(object, 2u);
  EXPECT_EQ(prim, 1u);
}

TEST(OsmesaBackend, ShadesLikeEveryOtherBackend) {
  // Colour comes from the shared shade_frame: the same IDs give the same colours.
  const Scene scene = test::analytic_scene({tilted_quad()});
  const CameraSpaceScene cs = CameraSpaceScene::build(scene);
  auto backend = make_osmesa_backend(cs, BackendConfig{.width = kSize, .height = kSize});
  Frame frame;
  backend->render(0.0, frame);
  shade_frame(cs, frame, 1);
  const PixelRays image{kSize, kSize};
  EXPECT_EQ(frame.color[frame.index(0, 0)], kBackgroundColor);
  EXPECT_EQ(frame.color[frame.index(12, 8)],
            shade_hit(cs, image, 12, 8, 0, frame.prim[frame.index(12, 8)], 0.0));
}

TEST(OsmesaBackend, AgreesWithEmbreeOnABuiltInSceneUpToTies) {
  // The budget of `kinray diff --against osmesa` is 0.1% of a frame's pixels; the built-in scenes
  // measure 0 real mismatches (docs/verification.md), and so must this one.
  const Scene scene = make_builtin_scene("static-moving", {{"triangles", 3000}});
  const CameraSpaceScene cs = CameraSpaceScene::build(scene);
  const BackendConfig config{.width = 160, .height = 120};
  auto osmesa = make_osmesa_backend(cs, config);
  auto embree = make_embree_backend(cs, config);
  FrameComparator comparator(cs);
  size_t ties = 0, hits = 0;
  for (double t : {0.0, 0.7, 1.4}) {
    Frame a, b;
    osmesa->render(t, a);
    embree->render(t, b);
    const FrameDiff diff = comparator.compare(a, b);
    EXPECT_EQ(diff.mismatch_real, 0u) << "t = " << t;
    ties += diff.mismatch_tie;
    for (uint32_t o : b.object) hits += o != kNoHit;
    // Where the IDs agree, so do the depths (both are the camera-space z of the same triangle).
    for (size_t p = 0; p < a.pixel_count(); ++p)
      if (diff.pixels[p] == PixelClass::kEqual) {
        ASSERT_NEAR(a.depth[p], b.depth[p], 2e-6 * b.depth[p]);
      }
  }
  EXPECT_GT(hits, 3 * 160 * 120 / 4);
  EXPECT_LT(ties, 3 * 160 * 120 / 100);
}

TEST(OsmesaBackend, RejectsImpossibleSizes) {
  const Scene scene = test::analytic_scene({tilted_quad()});
  const CameraSpaceScene cs = CameraSpaceScene::build(scene);
  EXPECT_THROW((void)make_osmesa_backend(cs, BackendConfig{.width = 0, .height = 8}), InputError);
  EXPECT_THROW((void)make_osmesa_backend(cs, BackendConfig{.width = 1 << 20, .height = 4}),
               InputError);
}

}  // namespace
}  // namespace kinray

#endif  // KINRAY_WITH_OSMESA
