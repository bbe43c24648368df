// Owner triangle pairs (primitive_owners.h): testing each primitive pair in one triangle pair
// finds exactly the contacts of testing it in every triangle pair that meets it, in general
// and in coplanar motion, where contact intervals must be reported the same whatever the order
// of the pair's points.
#include <gtest/gtest.h>

#include <random>

#include "kinetic/collision/mesh_contacts.h"
#include "kinetic/collision/primitive_owners.h"

namespace kinray {
namespace {

using V = Eigen::Vector3d;
using Triangle = std::array<std::uint32_t, 3>;

TEST(PrimitiveOwners, VertexTrianglesListsEachVertexsTrianglesInOrder) {
  const std::vector<Triangle> triangles = {{0, 1, 2}, {2, 1, 3}, {3, 3, 4}, {4, 0, 2}};
  const VertexTriangles around(triangles, 6);
  const auto list = [&](std::uint32_t v) {
    const std::span<const std::uint32_t> s = around.around(v);
    return std::vector<std::uint32_t>(s.begin(), s.end());
  };
  EXPECT_EQ(list(0), (std::vector<std::uint32_t>{0, 3}));
  EXPECT_EQ(list(2), (std::vector<std::uint32_t>{0, 1, 3}));
  EXPECT_EQ(list(3), (std::vector<std::uint32_t>{1, 2}));  // once, though twice in triangle 2
  EXPECT_TRUE(list(5).empty());
}

TEST(PrimitiveOwners, MasksBetweenMeshesFollowTheOwnerRule) {
  // owned_primitives between two meshes reads ranks kept per triangle; they must give the owner
  // rule's answer (owns_vertex_face, owns_edge_edge over each edge's triangles) for every pair,
  // with a fan of ten triangles around one edge (an incomplete list) and a degenerate triangle.
  std::vector<Triangle> fan = {{0, 1, 2}, {2, 1, 3}, {3, 3, 4}, {4, 0, 2}};
  for (std::uint32_t k = 0; k < 10; ++k) fan.push_back({5, 6, 7 + k});
  const std::vector<Triangle> grid = {{0, 1, 3}, {1, 4, 3}, {1, 2, 4}, {2, 5, 4}, {3, 4, 6}};
  const VertexTriangles fan_around(fan, 17), grid_around(grid, 7);
  const OwnerSide a{fan, &fan_around}, b{grid, &grid_around};
  for (std::uint32_t ta = 0; ta < fan.size(); ++ta)
    for (std::uint32_t tb = 0; tb < grid.size(); ++tb) {
      OwnedPrimitives expected = 0;
      for (int i = 0; i < 3; ++i) {
        if (owns_vertex_face(a, ta, fan[ta][i], b, tb, false)) expected |= 1u << (2 * i);
        if (owns_vertex_face(b, tb, grid[tb][i], a, ta, false)) expected |= 1u << (2 * i + 1);
        for (int j = 0; j < 3; ++j) {
          const EdgeTriangles ea = edge_triangles(fan_around, {fan[ta][i], fan[ta][(i + 1) % 3]});
          const EdgeTriangles eb =
              edge_triangles(grid_around, {grid[tb][j], grid[tb][(j + 1) % 3]});
          if (owns_edge_edge(a, ta, ea, b, tb, eb, false)) expected |= 1u << (6 + 3 * i + j);
        }
      }
      EXPECT_EQ(owned_primitives(a, ta, b, tb, false), expected) << ta << " " << tb;
      EXPECT_EQ(owned_primitives(b, tb, a, ta, false) != 0, expected != 0);
    }
}

/// A sheet of rows x columns quads (two triangles each) whose vertices move between random
/// keys; `flat` keeps every vertex in the plane z = 0, so every primitive pair moves coplanar.
struct Sheets {
  std::vector<Triangle> triangles;
  std::vector<std::vector<V>> start, end;  ///< per object
  std::uint32_t vertices = 0;

  Sheets(unsigned seed, int objects, int side, bool flat) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(-1, 1);
    const std::uint32_t n = std::uint32_t(side) + 1;
    vertices = n * n;
    for (std::uint32_t i = 0; i + 1 < n; ++i)
      for (std::uint32_t j = 0; j + 1 < n; ++j) {
        const std::uint32_t a = i * n + j, b = a + 1, c = a + n, d = c + 1;
        triangles.push_back({a, b, d});
        triangles.push_back({a, d, c});
      }
    for (int o = 0; o < objects; ++o) {
      for (auto* out : {&start, &end}) {
        const V centre(0.3 * u(rng), 0.3 * u(rng), flat ? 0 : 0.3 * u(rng));
        out->emplace_back();
        for (std::uint32_t v = 0; v < vertices; ++v) {
          const V jitter = 0.3 * V(u(rng), u(rng), flat ? 0 : u(rng));
          out->back().push_back(centre + V(0.2 * (v / n) - 0.4, 0.2 * (v % n) - 0.4, 0) + jitter);
        }
      }
    }
  }

  [[nodiscard]] std::vector<Contact> contacts(bool self, const VertexTriangles* around,
                                              PrimitiveCcdCounters& counters) const {
    std::vector<MeshSweep> meshes;
    for (std::uint32_t o = 0; o < start.size(); ++o)
      meshes.push_back({o, triangles, start[o], end[o], around});
    std::vector<Contact> out;
    ContactCounters all;
    for (std::uint32_t i = 0; i < meshes.size(); ++i)
      for (std::uint32_t j = self ? i : i + 1; j < meshes.size(); ++j)
        brute_force_contacts(meshes[i], meshes[j], 0, 1, out, all);
    sort_contacts(out);
    counters += all.primitives;
    return out;
  }
};

TEST(PrimitiveOwners, OwnersFindTheContactsOfEveryTrianglePairWithFewerTests) {
  std::size_t total = 0;
  for (bool flat : {false, true})
    for (unsigned seed = 1; seed <= 4; ++seed)
      for (bool self : {false, true}) {
        SCOPED_TRACE(::testing::Message()
                     << "seed " << seed << (flat ? " flat" : "") << (self ? " self" : ""));
        const Sheets sheets(seed, 2, 3, flat);
        const VertexTriangles around(sheets.triangles, sheets.vertices);
        PrimitiveCcdCounters every, owned;
        const std::vector<Contact> expected = sheets.contacts(self, nullptr, every);
        EXPECT_EQ(sheets.contacts(self, &around, owned), expected);
        EXPECT_LT(owned.tests * 2, every.tests);
        total += expected.size();
      }
  EXPECT_GT(total, 100u) << "the sheets touch";
}

}  // namespace
}  // namespace kinray
