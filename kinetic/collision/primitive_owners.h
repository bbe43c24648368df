#pragma once
// Which triangle pair tests a primitive pair. A vertex belongs to several triangles and an edge
// to two, so one vertex-face pair is met by up to six triangle pairs, one edge-edge pair by four
// (as many as there are triangles around the vertex, or around each edge), and every one of
// them overlaps whenever the primitives touch: the primitive's triangle contains it. Testing the
// primitive pair in one of them, its owner, finds the same contacts with a quarter of the
// primitive tests, for every contact finder alike (brute force, swept volumes, the list).
#include <array>
#include <cstdint>
#include <span>
#include <vector>

namespace kinray {

/// The triangles having an edge (around both its ends), in increasing order; `complete` is
/// false for an edge of more triangles than are kept (a non-manifold fan).
struct EdgeTriangles {
  std::array<std::uint32_t, 8> triangles{};
  std::uint32_t count = 0;
  bool complete = true;
};
class VertexTriangles;
[[nodiscard]] EdgeTriangles edge_triangles(const VertexTriangles& around,
                                           std::array<std::uint32_t, 2> edge);

/// The triangles around each vertex of one mesh, in increasing order (compressed rows), and the
/// triangles having each edge of each triangle: built once per mesh, so that the owners of a
/// triangle pair's primitive pairs (owned_primitives, asked by swept volumes and brute force for
/// every candidate pair of every check) do not intersect the vertices' lists again.
class VertexTriangles {
 public:
  VertexTriangles(std::span<const std::array<std::uint32_t, 3>> triangles,
                  std::uint32_t vertex_count);

  [[nodiscard]] std::span<const std::uint32_t> around(std::uint32_t vertex) const {
    return {m_triangles.data() + m_offsets[vertex], m_triangles.data() + m_offsets[vertex + 1]};
  }
  /// edge_triangles of triangle t's edge i (from its vertex i to i + 1).
  [[nodiscard]] const EdgeTriangles& edge(std::uint32_t t, int i) const {
    return m_edges[std::size_t(t)][std::size_t(i)];
  }
  /// Triangle t's ranks, one bit each: bit i, t is the lowest triangle around its vertex i; bit
  /// 3 + i, t is the lowest triangle of its edge i; bit 6 + i, that edge's list is incomplete.
  /// Between two meshes (no pair excluded) they are the owner rule.
  [[nodiscard]] std::uint16_t lowest(std::uint32_t t) const { return m_lowest[t]; }

 private:
  std::vector<std::uint32_t> m_offsets, m_triangles;
  std::vector<std::array<EdgeTriangles, 3>> m_edges;
  std::vector<std::uint16_t> m_lowest;
};

/// One side of a triangle pair: a mesh's triangles and the triangles around its vertices.
struct OwnerSide {
  std::span<const std::array<std::uint32_t, 3>> triangles;
  const VertexTriangles* around;
};

/// Whether triangle ta of `a` owns the test of its vertex v against face tb of `b`: ta is the
/// lowest-numbered triangle around v that may be paired with tb (with itself, `self`: shares
/// no vertex with it).
[[nodiscard]] bool owns_vertex_face(const OwnerSide& a, std::uint32_t ta, std::uint32_t v,
                                    const OwnerSide& b, std::uint32_t tb, bool self);

/// Whether triangle pair (ta, tb) owns the test of an edge of ta (its triangles `ea`) against
/// an edge of tb (`eb`): of the pairs of a triangle around each that may be paired, it is the
/// lowest (as an unordered pair, with itself). True too when a list is incomplete: the pair is
/// then tested by more than one triangle pair, and the repeated contacts are dropped.
[[nodiscard]] bool owns_edge_edge(const OwnerSide& a, std::uint32_t ta, const EdgeTriangles& ea,
                                  const OwnerSide& b, std::uint32_t tb, const EdgeTriangles& eb,
                                  bool self);

/// The primitive pairs a triangle pair owns, one bit each: bit 2 i is vertex i of ta against
/// face tb, bit 2 i + 1 vertex i of tb against face ta, bit 6 + 3 i + j edge i of ta (from its
/// vertex i to i + 1) against edge j of tb. It depends on the meshes' topology alone, so a
/// structure that keeps a triangle pair over several segments (the kinetic separation list)
/// computes it once.
using OwnedPrimitives = std::uint16_t;
constexpr OwnedPrimitives kAllPrimitives = 0x7FFF;
[[nodiscard]] OwnedPrimitives owned_primitives(const OwnerSide& a, std::uint32_t ta,
                                               const OwnerSide& b, std::uint32_t tb, bool self);

}  // namespace kinray
