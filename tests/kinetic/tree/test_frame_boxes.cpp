// The frame's compact float boxes: the same answers as brute force and as the lazy traversal, for
// the kinetic AABB tree, the kinetic BoxTree and the bottom-up tree, at random times.
#include <gtest/gtest.h>

#include <random>

#include "kinetic/tree/bottom_up_bvh.h"
#include "kinetic/tree/frame_boxes.h"
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
    const auto hit = frame_traverse(boxes, ray, false);
    ASSERT_EQ(hit.has_value(), expected.has_value());
    EXPECT_EQ(frame_traverse(boxes, ray, true).has_value(), expected.has_value());
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
