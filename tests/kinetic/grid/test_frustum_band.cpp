// FrustumBand's audit reports what it finds with where it found it (band, time, invariant, pixel
// or triangle and row) instead of aborting or throwing, for a corrupted band state and for a
// fault inside a pixel order.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "kinetic/grid/frustum_band.h"
#include "kinetic/grid/grid_scene.h"
#include "tests/kinetic/grid/grid_test_scenes.h"

namespace kinray {

/// The test hook FrustumBand names as its friend: changes a band behind its back.
struct FrustumBandTestAccess {
  /// Takes tri out of pixel (column, row)'s order without telling the band's records.
  static void erase_from_pixel(FrustumBand& band, uint32_t tri, int column, int row) {
    band.m_orders->erase(band.pixel_index(column, row), tri, band.m_sim.now());
  }
};

namespace {

using test::at_depth;
using test::TestScene;
using test::Vec;

// Triangle A stands at depth 2; B moves from depth 3 to 1 over [0, 1] and passes A at t = 0.5,
// so every pixel B covers holds both, and swaps them at 0.5.
TestScene two_triangles_that_swap() {
  TestScene scene;
  scene.width = 16;
  scene.height = 12;
  scene.meshes.push_back(test::moving_triangle(
      {0.0}, {{at_depth(-1.5, -1, 2), at_depth(1.5, -1, 2), at_depth(0, 1.5, 2)}}));
  auto b_at = [](double z) {
    return std::array<Vec, 3>{at_depth(-0.8, -0.6, z), at_depth(0.8, -0.6, z), at_depth(0, 0.7, z)};
  };
  scene.meshes.push_back(test::moving_triangle({0.0, 1.0}, {b_at(3), b_at(1)}));
  return scene;
}

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

TEST(FrustumBandAudit, CorruptedPixelIsReportedWithBandTimeInvariantAndPixel) {
  const TestScene scene = two_triangles_that_swap();
  const GridScene gs(scene.input());
  FrustumBand band(gs, 0, scene.height, {});
  band.start(0.0);
  band.advance_to(0.25);
  ASSERT_TRUE(band.audit(0.25).empty()) << band.audit(0.25).front();
  // The centre pixel holds both triangles; take A (triangle 0) out behind the band's back.
  const int column = scene.width / 2, row = scene.height / 2;
  ASSERT_EQ(band.depth_complexity(column, row), 2u);
  FrustumBandTestAccess::erase_from_pixel(band, 0, column, row);
  const std::vector<std::string> problems = band.audit(0.25);
  ASSERT_FALSE(problems.empty());
  const std::string pixel = "pixel (" + std::to_string(column) + ", " + std::to_string(row) + ")";
  bool pixel_set = false, in_order = false;
  for (const std::string& p : problems) {
    EXPECT_TRUE(contains(p, "band rows [0, 12) at t = 0.25: ")) << p;
    pixel_set |= contains(p, "pixel set: " + pixel + ": holds triangles that do not cover it");
    in_order |= contains(p, "record in pixel order: triangle 0 row " + std::to_string(row) +
                                " column " + std::to_string(column) + ": missing from the pixel order");
  }
  EXPECT_TRUE(pixel_set) << problems.front();
  EXPECT_TRUE(in_order) << problems.front();
}

// Audited at a time past its pending swaps, each pixel order's own audit finds a pair whose
// event was not processed: reported with the band, the pixel and the sort's own detail (the
// pair and its key values), not thrown out of the audit.
TEST(FrustumBandAudit, PixelOrderFaultIsReportedWithItsPixel) {
  const TestScene scene = two_triangles_that_swap();
  const GridScene gs(scene.input());
  FrustumBand band(gs, 0, scene.height, {});
  band.start(0.0);
  band.advance_to(0.25);
  std::vector<std::string> problems;
  ASSERT_NO_THROW(problems = band.audit(0.75, 1000));
  bool queue = false, order = false;
  for (const std::string& p : problems) {
    EXPECT_TRUE(contains(p, "band rows [0, 12) at t = 0.75: ")) << p;
    queue |= contains(p, "queue: an event at or before the audit time is still pending");
    order |= contains(p, "pixel order: pixel (" + std::to_string(scene.width / 2) + ", " +
                             std::to_string(scene.height / 2) + "): kinetic sort audit") &&
             contains(p, "pair (") && contains(p, "events not processed");
  }
  EXPECT_TRUE(queue);
  EXPECT_TRUE(order) << (problems.empty() ? std::string("no problems") : problems.front());
}

}  // namespace
}  // namespace kinray
