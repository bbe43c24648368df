// The near-miss scenes (glide, cloth-slide, swing): bodies that pass close and touch rarely. Every
// structure finds brute force's contacts, contact for contact, at positive, zero and negative
// gaps; a positive gap between the gliding spheres is a proof of no contact, so none is found.
#include <gtest/gtest.h>

#include <map>
#include <string>

#include "contacts/scene_contacts.h"
#include "scenes/procedural.h"
#include "util/input_error.h"

namespace kinray {
namespace {

std::vector<Contact> contacts(const Scene& scene, ContactStructure structure, int checks,
                              bool audit = false) {
  CollideParams params;
  params.structure = structure;
  params.checks = checks;
  params.audit = audit;
  return find_scene_contacts(scene, params).contacts;
}

/// ksl (audited, and asked 7 times a segment) and swept volumes (1 and 7 checks) against brute
/// force; returns brute force's contacts.
std::vector<Contact> expect_brute_force_contacts(const std::string& name, double gap) {
  SCOPED_TRACE(name + " gap " + std::to_string(gap));
  const Scene scene = make_builtin_scene(
      name, {{"triangles", 800}, {"duration", 1}, {"keyrate", 12}, {"gap", gap}});
  const std::vector<Contact> brute = contacts(scene, ContactStructure::brute, 1);
  EXPECT_EQ(contacts(scene, ContactStructure::ksl, 1, true), brute);
  EXPECT_EQ(contacts(scene, ContactStructure::ksl, 7), brute);
  EXPECT_EQ(contacts(scene, ContactStructure::swept, 1), brute);
  EXPECT_EQ(contacts(scene, ContactStructure::swept, 7), brute);
  return brute;
}

TEST(NearMissScenes, GlideMatchesBruteForceAndAPositiveGapNeverTouches) {
  EXPECT_TRUE(expect_brute_force_contacts("glide", 0.01).empty());
  (void)expect_brute_force_contacts("glide", 0);
  const size_t touching = expect_brute_force_contacts("glide", -0.06).size();
  EXPECT_GT(touching, 0u) << "the bulges meet at a negative gap";
  EXPECT_LT(touching, 200u) << "briefly";
}

TEST(NearMissScenes, ClothSlideMatchesBruteForce) {
  EXPECT_TRUE(expect_brute_force_contacts("cloth-slide", 0.05).empty());
  EXPECT_GT(expect_brute_force_contacts("cloth-slide", 0.01).size(), 0u) << "coarse cloth's chords";
  EXPECT_GT(expect_brute_force_contacts("cloth-slide", -0.01).size(), 0u);
}

// The articulated arm: the hand passes a positive gap above the floor without touching, and dips
// through it, briefly, at a negative one; the links never reach it.
TEST(NearMissScenes, SwingMatchesBruteForceAndAPositiveGapNeverTouches) {
  EXPECT_TRUE(expect_brute_force_contacts("swing", 0.01).empty());
  const size_t touching = expect_brute_force_contacts("swing", -0.02).size();
  EXPECT_GT(touching, 0u) << "the hand dips through the floor at a negative gap";
  EXPECT_LT(touching, 1000u) << "briefly";
}

// Where bodies only pass close, the list reads the trees near the passage alone: its lazy trees
// compute, over the shot, a small share of what an eager key pass computes (every node at every
// key), and find the same contacts (the test above).
TEST(NearMissScenes, TheListWakesTheTreesOnlyNearThePassage) {
  for (const char* name : {"glide", "swing"}) {
    SCOPED_TRACE(name);
    const Scene scene = make_builtin_scene(name, {{"triangles", 4000}, {"gap", -0.02}});
    CollideParams params;
    const SceneContacts found = find_scene_contacts(scene, params);
    ASSERT_TRUE(found.ksl.has_value());
    const double keyed = double(found.ksl->trees.nodes) * double(found.segments);
    EXPECT_GT(found.ksl->trees.nodes_woken, 0u);
    EXPECT_LT(double(found.ksl->trees.nodes_woken), 0.15 * keyed)
        << found.ksl->trees.nodes_woken << " nodes woken of " << keyed;
    EXPECT_GT(found.ksl->list.opened_at_keys, 0u) << "large sleeping pairs opened, not woken";
  }
}

TEST(NearMissScenes, OnlyTheyTakeAGap) {
  EXPECT_EQ(*builtin_scene_params("glide", {{"gap", -0.5}}).gap, -0.5);
  EXPECT_EQ(*builtin_scene_params("cloth-slide", {{"gap", 0}}).gap, 0.0);
  EXPECT_EQ(*builtin_scene_params("swing", {{"gap", 0.2}}).gap, 0.2);
  EXPECT_FALSE(builtin_scene_params("crossing", {}).gap.has_value());
  EXPECT_THROW((void)builtin_scene_params("crossing", {{"gap", 0.1}}), InputError);
  EXPECT_THROW((void)builtin_scene_params("glide", {{"gap", kInfinity}}), InputError);
}

}  // namespace
}  // namespace kinray
