// The kinetic AABB tree, the kinetic BoxTree and the bottom-up tree: audits, events, queries
// against brute force.
#include <gtest/gtest.h>

#include <random>
#include <string>

#include "kinetic/core/audit_failure.h"
#include "kinetic/tree/bottom_up_bvh.h"
#include "kinetic/tree/kinetic_bvh.h"
#include "tests/kinetic/tree/tree_test_scenes.h"

namespace kinray {

/// Corrupts a tree behind its back, as a bug would.
struct KineticBvhTestAccess {
  static void set_realizer(KineticBvh& tree, uint32_t node, int side, uint32_t vertex) {
    tree.m_node[node].realizer[size_t(side)] = vertex;
  }
  static void set_active(KineticBvh& tree, uint32_t node, bool active) {
    tree.m_node[node].active = active ? 1 : 0;
  }
};

namespace {

using test::Vec;

KineticBvh make_tree(const test::TestScene& scene, TreeShape shape, bool audit = true,
                     double t = 0) {
  return KineticBvh(scene.input().meshes, t, KineticBvh::Config{shape, audit});
}

TEST(KineticTree, AnalyticRealizerSwap) {
  // Two triangles move along x in opposite directions; their right-most vertices pass at t = 0.25
  // (x = 1 + t against x = 1.5 - t).
  test::TestScene scene;
  scene.meshes.push_back(test::moving_triangle(
      {0.0, 1.0},
      {{Vec(0, 0, 3), Vec(1, 0, 3), Vec(0, 1, 3)}, {Vec(1, 0, 3), Vec(2, 0, 3), Vec(1, 1, 3)}}));
  scene.meshes.push_back(
      test::moving_triangle({0.0, 1.0}, {{Vec(0.5, 2, 3), Vec(1.5, 2, 3), Vec(0.5, 3, 3)},
                                         {Vec(-0.5, 2, 3), Vec(0.5, 2, 3), Vec(-0.5, 3, 3)}}));
  for (TreeShape shape : {TreeShape::aabb, TreeShape::boxtree}) {
    KineticBvh tree = make_tree(scene, shape);
    const int max_x = side_of(0, true);
    const uint32_t root = 0;
    if (shape == TreeShape::aabb) {
      EXPECT_EQ(tree.realizer(root, max_x), 4u);  // mesh 1's vertex 1 (global 3 + 1)
      tree.advance_to(0.24);
      EXPECT_EQ(tree.realizer(root, max_x), 4u);
      tree.advance_to(0.26);
      EXPECT_EQ(tree.realizer(root, max_x), 1u);
      EXPECT_DOUBLE_EQ(tree.side_value(root, max_x, 0.75), 1.75);
    }
    tree.advance_to(2.0);
    const TreeStats s = tree.stats();
    EXPECT_GE(s.events.tree, shape == TreeShape::aabb ? 1u : 0u);
    EXPECT_EQ(s.events.flightplan, 2u);  // each mesh reaches its last key once
    EXPECT_EQ(s.events.leaf, 0u);        // the triangles translate: no vertex overtakes another
  }
}

TEST(KineticTree, AuditedThroughRandomMotion) {
  for (uint32_t seed : {1u, 2u, 3u}) {
    const test::TestScene scene = test::mixed_tree_scene(seed);
    for (TreeShape shape : {TreeShape::aabb, TreeShape::boxtree}) {
      KineticBvh tree = make_tree(scene, shape);  // audits after every advance_to
      for (double t = 0.05; t < 3.5; t += 0.05) tree.advance_to(t);
      const TreeStats s = tree.stats();
      EXPECT_GT(s.events.leaf, 0u);
      EXPECT_GT(s.events.tree, 0u);
      EXPECT_EQ(s.events.insert, 1u);
      EXPECT_EQ(s.events.remove, 1u);
      EXPECT_GT(s.events.flightplan, 0u);
    }
  }
}

TEST(KineticTree, AuditedWhenRoundedCoordinatesInvertTheCertificateOrder) {
  // Two vertices of cloth-fold --self (453 and 486 on the min-x side of a leaf): one ulp apart in
  // x at the first key, equal at the second, so their slopes differ by one ulp and their exact
  // motions a + b (t - o) cross near s = 1/64 of the way. Afterwards the tree's certificate
  // (c0 + c1 s, exact coefficients) puts 486 below 453 by a few 1e-18, while the rounded
  // coordinates can put 453 below by as much: the audit compares in the tree's order, and the
  // coordinates within their rounding.
  test::TestScene scene;
  scene.meshes.push_back(
      test::moving_triangle({11.0 / 12, 23.0 / 24},
                            {{Vec(0.021557424117480291, 0, 1), Vec(0.021557424117480295, 0.1, 1),
                              Vec(0.038179781922915983, 0.2, 1.1)},
                             {Vec(-0.032733060360947829, 0, 1), Vec(-0.032733060360947829, 0.1, 1),
                              Vec(-0.02291395559729361, 0.2, 1.1)}}));
  for (TreeShape shape : {TreeShape::aabb, TreeShape::boxtree}) {
    KineticBvh tree = make_tree(scene, shape, true, 11.0 / 12);  // audits after every advance_to
    for (int k = 1; k <= 2000; ++k) tree.advance_to(11.0 / 12 + k / (24.0 * 2000));
    EXPECT_EQ(tree.stats().events.leaf, shape == TreeShape::aabb ? 1u : 0u);
  }
}

// A lazy tree sleeps at keys and computes a node when woken: whatever it woke, at any time, holds
// the realizers the eager tree holds then, and the audit (run after every advance) finds every
// awake node's certificates scheduled and no sleeping node with one.
TEST(KineticTree, ALazyTreeWokenAnywhereEqualsTheEagerTree) {
  for (uint32_t seed : {1u, 2u, 3u}) {
    const test::TestScene scene = test::mixed_tree_scene(seed);
    for (TreeShape shape : {TreeShape::aabb, TreeShape::boxtree}) {
      SCOPED_TRACE(::testing::Message() << "seed " << seed << " shape " << int(shape));
      KineticBvh eager = make_tree(scene, shape);
      KineticBvh lazy(scene.input().meshes, 0, KineticBvh::Config{shape, true, true});
      std::mt19937 rng(seed);
      const uint32_t nodes = uint32_t(lazy.topology().nodes.size());
      uint64_t asleep_seen = 0;
      for (double t = 0.05; t < 3.5; t += 0.05) {
        eager.advance_to(t);
        lazy.advance_to(t);
        for (uint32_t i = 0; i < nodes; ++i) asleep_seen += !lazy.awake(i);
        const uint32_t node = std::uniform_int_distribution<uint32_t>(0, nodes - 1)(rng);
        lazy.wake(node);
        EXPECT_TRUE(lazy.awake(node));
        lazy.audit();
        for (uint32_t i = 0; i < nodes; ++i) {
          if (!lazy.awake(i)) continue;
          for (int side = 0; side < 6; ++side)
            ASSERT_EQ(lazy.realizer(i, side), eager.realizer(i, side))
                << "node " << i << " side " << side << " at t = " << t;
        }
      }
      EXPECT_GT(asleep_seen, 0u) << "keys put nodes to sleep";
      lazy.wake(0);
      for (uint32_t i = 0; i < nodes; ++i) EXPECT_TRUE(lazy.awake(i));
    }
  }
}

TEST(KineticTree, EventsIndependentOfFramesQueried) {
  const test::TestScene scene = test::mixed_tree_scene(7);
  for (TreeShape shape : {TreeShape::aabb, TreeShape::boxtree}) {
    KineticBvh once = make_tree(scene, shape, false);
    once.advance_to(3.0);
    KineticBvh often = make_tree(scene, shape, false);
    for (int f = 1; f <= 300; ++f) often.advance_to(3.0 * f / 300);
    const TreeStats a = once.stats(), b = often.stats();
    EXPECT_EQ(a.events.leaf, b.events.leaf);
    EXPECT_EQ(a.events.tree, b.events.tree);
    EXPECT_EQ(a.events.total(), b.events.total());
    EXPECT_EQ(a.certificates_computed, b.certificates_computed);
  }
}

TEST(KineticTree, StaticMeshesEmitNoEvents) {
  std::mt19937 rng(3);
  test::TestScene scene;
  test::OwnedMesh ground = test::deforming_grid(rng, 8, 8, {0.0, 1.0}, 0.1, 4.0);
  ground.positions.resize(ground.vertex_count);
  ground.positions.insert(ground.positions.end(), ground.positions.begin(), ground.positions.end());
  ground.is_static = true;
  scene.meshes.push_back(ground);
  KineticBvh tree = make_tree(scene, TreeShape::aabb);
  tree.advance_to(5.0);
  EXPECT_EQ(tree.stats().events.total(), 0u);
  EXPECT_EQ(tree.stats().scheduled_events, 0u);
}

TEST(KineticTree, BoxTreeTracksFewerSidesAndHasFewerEvents) {
  const test::TestScene scene = test::mixed_tree_scene(11, 24);
  KineticBvh aabb = make_tree(scene, TreeShape::aabb, false);
  KineticBvh box = make_tree(scene, TreeShape::boxtree, false);
  aabb.advance_to(3.0);
  box.advance_to(3.0);
  EXPECT_LT(box.stats().node_sides, aabb.stats().node_sides);
  EXPECT_LT(box.stats().events.failures(), aabb.stats().events.failures());
  EXPECT_LT(box.stats().certificates_live, aabb.stats().certificates_live);
}

template <class Tree>
void expect_queries_match_brute_force(const Tree& tree, const TreeFrame& frame, std::mt19937& rng,
                                      int& hits) {
  for (int r = 0; r < 200; ++r) {
    TreeRay ray = test::random_tree_ray(rng);
    const auto brute = brute_force_closest_hit(tree.meshes(), ray, frame);
    if (brute && rng() % 4 == 0) ray.skip = brute->triangle;  // the shadow rays' rule
    const auto expected = brute_force_closest_hit(tree.meshes(), ray, frame);
    const auto hit = closest_hit(tree, ray, frame);
    ASSERT_EQ(hit.has_value(), expected.has_value());
    EXPECT_EQ(any_hit(tree, ray, frame), expected.has_value());
    if (hit) {
      ++hits;
      EXPECT_EQ(hit->s, expected->s);  // the same triangle, or one at exactly the same parameter
      if (hit->triangle != expected->triangle) {
        EXPECT_NE(hit->triangle, ray.skip);
      }
    }
  }
}

TEST(KineticTree, QueriesMatchBruteForceAtRandomTimes) {
  const test::TestScene scene = test::mixed_tree_scene(5);
  std::mt19937 rng(99);
  int hits = 0;
  test::for_each_tree_at_random_times(scene, rng, 0.2,
                                      [&](const auto& tree, const TreeFrame& frame) {
                                        expect_queries_match_brute_force(tree, frame, rng, hits);
                                      });
  EXPECT_GT(hits, 1000);  // the rays do meet the triangles
}

TEST(KineticTree, SameShapeAsBottomUpAndBoxesEqualAtFrames) {
  const test::TestScene scene = test::mixed_tree_scene(8);
  KineticBvh aabb = make_tree(scene, TreeShape::aabb);
  BottomUpBvh bottom_up(scene.input().meshes, 0);
  ASSERT_EQ(aabb.topology().nodes.size(), bottom_up.topology().nodes.size());
  for (double t : {0.3, 1.1, 2.9}) {
    aabb.advance_to(t);
    bottom_up.update(t);
    for (uint32_t i = 0; i < aabb.topology().nodes.size(); ++i) {
      ASSERT_EQ(aabb.topology().nodes[i].triangle, bottom_up.topology().nodes[i].triangle);
      if (!aabb.active(i)) continue;
      for (int s = 0; s < 6; ++s) {
        const double exact = side_sign(s) > 0 ? bottom_up.box(i).hi[side_axis(s)]
                                              : bottom_up.box(i).lo[side_axis(s)];
        EXPECT_NEAR(aabb.side_value(i, s, t), exact, 1e-12 * aabb.meshes().scale());
      }
    }
  }
}

TEST(KineticTree, MalformedMeshesThrow) {
  test::TestScene scene;
  scene.meshes.push_back(
      test::moving_triangle({0.0, 1.0}, {{Vec(0, 0, 3), Vec(1, 0, 3), Vec(0, 1, 3)}}));
  EXPECT_THROW(make_tree(scene, TreeShape::aabb), std::invalid_argument);
}

}  // namespace
}  // namespace kinray

namespace kinray {
namespace {

// The audit is what the other tests lean on: shown here to catch a wrong realizer and a wrong
// presence, naming the node and side, on both tree shapes.
TEST(KineticTreeAudit, ACorruptedRealizerOrPresenceIsReportedWithItsNodeAndSide) {
  const test::TestScene scene = test::mixed_tree_scene(4, 6);
  for (TreeShape shape : {TreeShape::aabb, TreeShape::boxtree}) {
    SCOPED_TRACE(shape == TreeShape::aabb ? "aabb" : "boxtree");
    KineticBvh tree = make_tree(scene, shape, false);
    tree.advance_to(0.3);
    ASSERT_NO_THROW(tree.audit());
    // the first tracked side of an inner node (a BoxTree's root tracks none)
    uint32_t node = 0;
    int side = 6;
    for (; node < tree.topology().nodes.size() && side == 6; ++node) {
      if (tree.topology().nodes[node].leaf()) continue;
      side = 0;
      while (side < 6 && tree.realizer(node, side) == kNoVertex) ++side;
      if (side < 6) break;
    }
    ASSERT_LT(side, 6);
    const uint32_t extreme = tree.realizer(node, side);
    KineticBvhTestAccess::set_realizer(tree, node, side, extreme == 0 ? 1 : 0);
    try {
      tree.audit();
      ADD_FAILURE() << "the audit missed a wrong realizer";
    } catch (const KineticAuditFailure& failure) {
      const std::string report = failure.what();
      EXPECT_NE(report.find("node " + std::to_string(node) + " side " + std::to_string(side)),
                std::string::npos)
          << report;
      EXPECT_NE(report.find("differs from the extreme of its leaves"), std::string::npos) << report;
    }
    KineticBvhTestAccess::set_realizer(tree, node, side, extreme);
    ASSERT_NO_THROW(tree.audit());
    const uint32_t root = 0;
    KineticBvhTestAccess::set_active(tree, root, false);
    try {
      tree.audit();
      ADD_FAILURE() << "the audit missed a wrong presence";
    } catch (const KineticAuditFailure& failure) {
      EXPECT_NE(std::string(failure.what()).find("wrong presence"), std::string::npos)
          << failure.what();
    }
  }
}

}  // namespace
}  // namespace kinray
