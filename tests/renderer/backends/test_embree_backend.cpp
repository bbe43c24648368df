// The Embree backend on analytic scenes: a quad at a known depth parallel to the image plane
// (every pixel's object, primitive and depth exact), a tilted quad (depth against the analytic
// plane), and a moving scene on which every mode and packet width must agree.
#include <gtest/gtest.h>

#include <algorithm>
#include <iostream>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "renderer/backends/backend.h"
#include "renderer/backends/embree_backend.h"
#include "scenes/camera_space.h"
#include "scenes/scene.h"
#include "util/input_error.h"

namespace kinray {
namespace {

constexpr int kWidth = 64, kHeight = 48;

/// A camera at the origin looking down world -z with a 90 degree vertical fov, so camera-space
/// (x, y, z) is world (x, y, -z) (the fov scale 1 / tan(45 deg) is 1 up to an ulp of double).
Scene empty_scene() {
  Scene scene;
  scene.name = "analytic";
  scene.camera.keys = {CameraKey{}};
  scene.camera.keys[0].fov_y_degrees = 90;
  scene.time_begin = 0;
  scene.time_end = 1;
  return scene;
}

/// A static quad with camera-space corners a, b, c, d (triangles abc and acd).
Object quad(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  auto world = [](const Vec3& p) { return Vec3(p.x(), p.y(), -p.z()); };
  Object object;
  object.name = "quad";
  object.triangles = {Triangle{0, 1, 2}, Triangle{0, 2, 3}};
  object.key_times = {0};
  object.key_positions = {{world(a), world(b), world(c), world(d)}};
  return object;
}

BackendConfig config(const std::string& mode, int packet) {
  BackendConfig c;
  c.width = kWidth;
  c.height = kHeight;
  c.threads = 2;
  c.embree_build = find_enum(kEmbreeBuildNames, mode).value();
  c.embree_packet = packet;
  return c;
}

/// Side of the line through p and q on which (x, y) lies (> 0: left).
double side(double px, double py, double qx, double qy, double x, double y) {
  return (qx - px) * (y - py) - (qy - py) * (x - px);
}

TEST(EmbreeBackend, QuadParallelToImagePlaneHasExactIdsAndDepth) {
  const PixelRays image{kWidth, kHeight};
  const double z = 3;
  // Columns [i0, i1) and rows [j0, j1) are covered: the quad's edges lie half-way between pixel
  // centres (scaled by the depth), so no centre ray is near an edge.
  const int i0 = 11, i1 = 41, j0 = 7, j1 = 30;
  const double x0 = z * 0.5 * (image.x(i0 - 1) + image.x(i0));
  const double x1 = z * 0.5 * (image.x(i1 - 1) + image.x(i1));
  const double y0 = z * 0.5 * (image.y(j1 - 1) + image.y(j1));  // bottom
  const double y1 = z * 0.5 * (image.y(j0 - 1) + image.y(j0));  // top
  Scene scene = empty_scene();
  scene.objects.push_back(quad({x0, y0, z}, {x1, y0, z}, {x1, y1, z}, {x0, y1, z}));
  scene.validate("test");
  const CameraSpaceScene cs = CameraSpaceScene::build(scene);

  for (const std::string mode : {"rebuild", "refit"}) {
    for (int packet : embree_packet_widths()) {
      SCOPED_TRACE(mode + " packet " + std::to_string(packet));
      auto backend = make_embree_backend(cs, config(mode, packet));
      EXPECT_EQ(backend->name(), "embree");
      Frame frame;
      backend->render(0.5, frame);
      ASSERT_EQ(frame.width, kWidth);
      ASSERT_EQ(frame.height, kHeight);
      EXPECT_EQ(frame.time, 0.5);
      int checked_prims = 0;
      for (int j = 0; j < kHeight; ++j) {
        for (int i = 0; i < kWidth; ++i) {
          const size_t p = frame.index(i, j);
          const bool inside = i >= i0 && i < i1 && j >= j0 && j < j1;
          if (!inside) {
            EXPECT_EQ(frame.object[p], kNoHit) << i << "," << j;
            EXPECT_EQ(frame.prim[p], kNoHit);
            EXPECT_TRUE(std::isinf(frame.depth[p]));
            continue;
          }
          EXPECT_EQ(frame.object[p], 0u) << i << "," << j;
          EXPECT_EQ(frame.depth[p], 3.0f) << i << "," << j;
          // Triangle 0 (a, b, c) lies right of the diagonal a -> c.
          const double s = side(x0, y0, x1, y1, z * image.x(i), z * image.y(j));
          if (std::abs(s) < 1e-6) continue;  // on the diagonal: a tie between the two triangles
          EXPECT_EQ(frame.prim[p], s < 0 ? 0u : 1u) << i << "," << j;
          ++checked_prims;
        }
      }
      EXPECT_GT(checked_prims, (i1 - i0) * (j1 - j0) * 9 / 10);
    }
  }
}

TEST(EmbreeBackend, TiltedQuadDepthFollowsTheAnalyticPlane) {
  // The plane z = 3 + 0.5 x + 0.25 y; along d = (x_i, y_j, 1) its depth is 3 / (1 - 0.5 x_i - 0.25
  // y_j).
  auto plane = [](double x, double y) { return Vec3(x, y, 3 + 0.5 * x + 0.25 * y); };
  Scene scene = empty_scene();
  scene.objects.push_back(
      quad(plane(-1.5, -1.2), plane(1.4, -1.2), plane(1.4, 1.1), plane(-1.5, 1.1)));
  const CameraSpaceScene cs = CameraSpaceScene::build(scene);
  const PixelRays image{kWidth, kHeight};
  for (int packet : {1, embree_packet_widths().back()}) {
    auto backend = make_embree_backend(cs, config("refit", packet));
    Frame frame;
    backend->render(0, frame);
    int hits = 0;
    for (int j = 0; j < kHeight; ++j) {
      for (int i = 0; i < kWidth; ++i) {
        const double x = image.x(i), y = image.y(j);
        const double depth = 3 / (1 - 0.5 * x - 0.25 * y);
        const Vec3 hit = depth * image.direction(i, j);
        const size_t p = frame.index(i, j);
        const double margin = 1e-3;
        const bool inside = hit.x() > -1.5 + margin && hit.x() < 1.4 - margin &&
                            hit.y() > -1.2 + margin && hit.y() < 1.1 - margin;
        const bool outside = hit.x() < -1.5 - margin || hit.x() > 1.4 + margin ||
                             hit.y() < -1.2 - margin || hit.y() > 1.1 + margin;
        if (inside) {
          ++hits;
          ASSERT_EQ(frame.object[p], 0u) << i << "," << j;
          EXPECT_NEAR(frame.depth[p], depth, depth * 1.2e-7) << i << "," << j;
        } else if (outside) {
          EXPECT_EQ(frame.object[p], kNoHit) << i << "," << j;
        }
      }
    }
    EXPECT_GT(hits, 400);  // about a sixth of the image
  }
}

/// A lumpy sphere (UV grid) that breathes over three keys, off-centre so that no vertex lies on a
/// pixel-centre ray plane by symmetry.
Object breathing_sphere() {
  Object object;
  object.name = "sphere";
  const int rings = 14, segments = 22;
  const Vec3 centre(0.13, -0.07, -4.1);
  object.key_times = {0, 0.5, 1};
  object.key_positions.resize(3);
  for (int r = 0; r <= rings; ++r) {
    for (int s = 0; s < segments; ++s) {
      const double theta = std::numbers::pi * r / rings,
                   phi = 2 * std::numbers::pi * s / segments + 0.1;
      const Vec3 n(std::sin(theta) * std::cos(phi), std::cos(theta),
                   std::sin(theta) * std::sin(phi));
      for (int k = 0; k < 3; ++k) {
        const double radius = 1.1 + 0.25 * std::sin(3 * theta + 2 * phi + 1.7 * k);
        object.key_positions[size_t(k)].push_back(centre + radius * n + Vec3(0.3 * k, 0.1 * k, 0));
      }
    }
  }
  for (int r = 0; r < rings; ++r) {
    for (int s = 0; s < segments; ++s) {
      const uint32_t a = uint32_t(r * segments + s),
                     b = uint32_t(r * segments + (s + 1) % segments);
      const uint32_t c = a + uint32_t(segments), d = b + uint32_t(segments);
      object.triangles.push_back({a, c, b});
      object.triangles.push_back({b, c, d});
    }
  }
  return object;
}

TEST(EmbreeBackend, ModesAndPacketWidthsAgreeOnAMovingScene) {
  Scene scene = empty_scene();
  scene.objects.push_back(breathing_sphere());
  Object wall = quad({-6, -5, 7.3}, {6.5, -5.2, 6.1}, {6.1, 4.8, 6.6}, {-6.2, 5.1, 7.9});
  wall.name = "wall";
  scene.objects.push_back(wall);
  Object flash = quad({-0.9, -0.4, 2.2}, {-0.1, -0.5, 2.4}, {-0.2, 0.3, 2.3}, {-1.0, 0.35, 2.1});
  flash.name = "flash";
  flash.appear = 0.3;
  flash.disappear = 0.7;
  scene.objects.push_back(flash);
  scene.validate("test");
  const CameraSpaceScene cs = CameraSpaceScene::build(scene);
  const std::vector<double> times = {0, 0.2, 0.35, 0.5, 0.65, 0.8, 1};

  auto render_all = [&](const std::string& mode, int packet) {
    auto backend = make_embree_backend(cs, config(mode, packet));
    std::vector<Frame> frames(times.size());
    for (size_t f = 0; f < times.size(); ++f) backend->render(times[f], frames[f]);
    return frames;
  };
  const std::vector<Frame> reference = render_all("rebuild", 1);
  for (size_t f = 0; f < times.size(); ++f) {
    size_t sphere = 0, wall_pixels = 0, flash_pixels = 0;
    for (uint32_t object : reference[f].object) {
      sphere += object == 0;
      wall_pixels += object == 1;
      flash_pixels += object == 2;
    }
    EXPECT_GT(sphere, 100u) << "t=" << times[f];
    EXPECT_GT(wall_pixels, 100u) << "t=" << times[f];
    EXPECT_EQ(flash_pixels > 0, times[f] >= 0.3 && times[f] < 0.7) << "t=" << times[f];
  }
  EXPECT_NE(reference[0].object, reference[3].object) << "the sphere should move";

  for (const std::string mode : {"rebuild", "refit"}) {
    for (int packet : embree_packet_widths()) {
      if (mode == "rebuild" && packet == 1) continue;
      SCOPED_TRACE(mode + " packet " + std::to_string(packet));
      const std::vector<Frame> frames = render_all(mode, packet);
      for (size_t f = 0; f < times.size(); ++f) {
        EXPECT_EQ(frames[f].object, reference[f].object) << "t=" << times[f];
        EXPECT_EQ(frames[f].prim, reference[f].prim) << "t=" << times[f];
        EXPECT_EQ(frames[f].depth, reference[f].depth) << "t=" << times[f];
      }
    }
  }
}

// The tests above run every packet width this machine's Embree traces natively; on a CPU without
// AVX-512 there are no 16-wide packets, and asking for them must be refused with a clear line.
TEST(EmbreeBackend, PacketWidthsAreWhatTheMachineOffers) {
  const std::vector<int> widths = embree_packet_widths();
  ASSERT_FALSE(widths.empty());
  EXPECT_EQ(widths.front(), 1);
  EXPECT_TRUE(std::is_sorted(widths.begin(), widths.end()));
  Scene scene = empty_scene();
  scene.objects.push_back(quad({-1, -1, 3}, {1, -1, 3}, {1, 1, 3}, {-1, 1, 3}));
  const CameraSpaceScene cs = CameraSpaceScene::build(scene);
  for (int packet : {4, 8, 16}) {
    if (std::find(widths.begin(), widths.end(), packet) != widths.end()) continue;
    std::cout << "[   NOTE   ] this machine's Embree has no native " << packet
              << "-wide ray packets: the tests above skip them\n";
    try {
      (void)make_embree_backend(cs, config("refit", packet));
      ADD_FAILURE() << packet << "-wide packets were accepted though not native";
    } catch (const OptionError& e) {
      EXPECT_EQ(e.where(), "embree_packet") << e.what();  // the CLI names --packet
      EXPECT_NE(e.message().find("no native"), std::string::npos) << e.what();
    }
  }
}

TEST(EmbreeBackend, RejectsBadModesAndPacketWidths) {
  Scene scene = empty_scene();
  scene.objects.push_back(quad({-1, -1, 3}, {1, -1, 3}, {1, 1, 3}, {-1, 1, 3}));
  const CameraSpaceScene cs = CameraSpaceScene::build(scene);
  EXPECT_THROW((void)make_embree_backend(cs, config("refit", 3)), OptionError);
  BackendConfig empty = config("rebuild", 1);
  empty.width = 0;
  EXPECT_THROW((void)make_embree_backend(cs, empty), OptionError);
  EXPECT_THROW((void)make_backend("raytracer-9000", cs, config("refit", 1)), InputError);
  EXPECT_EQ(make_backend("embree", cs, config("refit", 1))->name(), "embree");
}

}  // namespace
}  // namespace kinray
