// The frame's compact float boxes: the same answers as brute force and as the lazy traversal, for
// the kinetic AABB tree, the kinetic BoxTree and the bottom-up tree, at random times.
#include <gtest/gtest.h>

#include <random>

#include "kinetic/tree/bottom_up_bvh.h"
#include "kinetic/tree/frame_boxes.h"
#include "kinetic/tree/frame_occlusion.h"
#include "kinetic/tree/kinetic_bvh.h"
#include "tests/kinetic/tree/tree_test_scenes.h"

namespace kinray {
namespace {

template <class Tree>
void expect_frame_queries_match(const Tree& tree, const TreeFrame& frame, std::mt19937& rng,
                                int& hits) {
  FrameBoxes boxes;
  boxes.fill(tree, frame);
  for (int r = 0; r < 200; ++r) {
    TreeRay ray = test::random_tree_ray(rng);
    const auto first = brute_force_closest_hit(tree.meshes(), ray, frame);
    if (first && rng() % 4 == 0) ray.skip = first->triangle;  // the shadow rays' rule
    const auto expected = brute_force_closest_hit(tree.meshes(), ray, frame);
    const auto hit = frame_closest_hit(boxes, ray);
    ASSERT_EQ(hit.has_value(), expected.has_value());
    uint8_t blocked = 7;
    frame_occluded(boxes, std::span<const TreeRay>(&ray, 1), std::span<uint8_t>(&blocked, 1));
    EXPECT_EQ(blocked, expected.has_value() ? 1 : 0);
    EXPECT_EQ(any_hit(tree, ray, frame), expected.has_value());  // the lazy traversal agrees
    if (!hit) continue;
    ++hits;
    EXPECT_EQ(hit->s, expected->s);  // the same triangle, or one at exactly the same parameter
    EXPECT_NE(hit->triangle, ray.skip);
  }
}

TEST(FrameBoxes, QueriesMatchBruteForceAndTheLazyTraversal) {
  const test::TestScene scene = test::mixed_tree_scene(6);
  std::mt19937 rng(17);
  int hits = 0;
  test::for_each_tree_at_random_times(scene, rng, 0.25,
                                      [&](const auto& tree, const TreeFrame& frame) {
                                        expect_frame_queries_match(tree, frame, rng, hits);
                                      });
  EXPECT_GT(hits, 1000);
}

TEST(FrameBoxes, InterleavedOcclusionAnswersAsOneRayAtATime) {
  const test::TestScene scene = test::mixed_tree_scene(4);
  std::mt19937 rng(23);
  int blocked_total = 0, rays_total = 0;
  test::for_each_tree_at_random_times(
      scene, rng, 0.4, [&](const auto& tree, const TreeFrame& frame) {
        FrameBoxes boxes;
        boxes.fill(tree, frame);
        // More rays than lanes, in a count that leaves lanes idle at the end; some skip the
        // triangle they would hit first (the shadow rays' rule).
        std::vector<TreeRay> rays(37 + rng() % 50);
        for (TreeRay& ray : rays) {
          ray = test::random_tree_ray(rng);
          const auto first = frame_closest_hit(boxes, ray);
          if (first && rng() % 3 == 0) ray.skip = first->triangle;
        }
        std::vector<uint8_t> blocked(rays.size(), 7);
        frame_occluded(boxes, rays, blocked);
        for (size_t i = 0; i < rays.size(); ++i) {
          const bool expected = brute_force_closest_hit(tree.meshes(), rays[i], frame).has_value();
          ASSERT_EQ(blocked[i], expected ? 1 : 0) << "ray " << i;
          blocked_total += blocked[i];
        }
        rays_total += int(rays.size());
      });
  // Both answers occur often (the rays are aimed into the scene).
  EXPECT_GT(blocked_total, rays_total / 10);
  EXPECT_LT(blocked_total, rays_total * 9 / 10);
}

TEST(FrameBoxes, ATrackedCopyOfTheRealizersStaysTheTreesOwn) {
  // The wide nodes' copy of the AABB tree's realizers, kept by its observer through events,
  // keys and a mesh that appears and disappears, gives the boxes of a copy made afresh.
  const test::TestScene scene = test::mixed_tree_scene(11);
  KineticBvh aabb(scene.input().meshes, 0, KineticBvh::Config{TreeShape::aabb, false});
  FrameBoxes tracked;
  tracked.track(aabb);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> dt(0, 0.15);
  int compared = 0;
  for (double t = 0; t < 3.4; t += dt(rng)) {
    aabb.advance_to(t);
    const TreeFrame frame(aabb.meshes(), t);
    tracked.fill(aabb, frame);
    FrameBoxes fresh;
    fresh.fill(aabb, frame);
    for (uint32_t i = 1; i < aabb.topology().nodes.size(); ++i) {
      const auto a = tracked.box_of(i), b = fresh.box_of(i);
      ASSERT_EQ(a.has_value(), b.has_value());
      if (!a) continue;
      ASSERT_EQ(*a, *b) << "node " << i << " at t = " << t;
      ++compared;
    }
  }
  EXPECT_GT(compared, 10000);
}

TEST(FrameBoxes, FloatBoxesContainTheKineticBoxes) {
  const test::TestScene scene = test::mixed_tree_scene(9);
  KineticBvh aabb(scene.input().meshes, 0, KineticBvh::Config{TreeShape::aabb, false});
  for (double t : {0.4, 1.7, 3.1}) {
    aabb.advance_to(t);
    const TreeFrame frame(aabb.meshes(), t);
    FrameBoxes boxes;
    boxes.fill(aabb, frame);
    const auto& nodes = aabb.topology().nodes;
    int stored = 0;
    for (uint32_t i = 0; i < nodes.size(); ++i) {
      const std::optional<std::array<float, 6>> box =
          i == 0 ? std::optional(boxes.root_box()) : boxes.box_of(i);
      if (!box) {
        EXPECT_FALSE(nodes[i].leaf());  // only inner nodes are opened by the collapse
        continue;
      }
      ++stored;
      if (!aabb.active(i)) {
        EXPECT_GT((*box)[0], (*box)[3]);  // empty
        continue;
      }
      for (int s = 0; s < 6; ++s) {
        const int a = side_axis(s);
        const double v = aabb.side_value(i, s, t);
        if (side_sign(s) > 0)
          EXPECT_GE(double((*box)[size_t(a) + 3]), v + frame.pad);
        else
          EXPECT_LE(double((*box)[size_t(a)]), v - frame.pad);
      }
    }
    // Four children per wide node, so about two thirds of the nodes are stored.
    EXPECT_GT(stored, int(nodes.size()) / 2);
  }
}

}  // namespace
}  // namespace kinray
