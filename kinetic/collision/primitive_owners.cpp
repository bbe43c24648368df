#include "kinetic/collision/primitive_owners.h"

#include <algorithm>
#include <utility>

#include "kinetic/collision/mesh_contacts.h"

namespace kinray {
namespace {

bool may_pair(const OwnerSide& a, std::uint32_t ta, std::uint32_t tb, bool self) {
  return !self || (ta != tb && !triangles_adjacent(a.triangles[ta], a.triangles[tb]));
}

}  // namespace

VertexTriangles::VertexTriangles(std::span<const std::array<std::uint32_t, 3>> triangles,
                                 std::uint32_t vertex_count)
    : m_offsets(std::size_t(vertex_count) + 1, 0) {
  // a vertex repeated in a degenerate triangle counts once
  const auto distinct = [](const std::array<std::uint32_t, 3>& t, int i) {
    return i == 0 || (i == 1 ? t[1] != t[0] : t[2] != t[0] && t[2] != t[1]);
  };
  for (const std::array<std::uint32_t, 3>& t : triangles)
    for (int i = 0; i < 3; ++i)
      if (distinct(t, i)) ++m_offsets[t[i] + 1];
  for (std::uint32_t v = 0; v < vertex_count; ++v) m_offsets[v + 1] += m_offsets[v];
  m_triangles.resize(m_offsets.back());
  std::vector<std::uint32_t> next(m_offsets.begin(), m_offsets.end() - 1);
  for (std::uint32_t k = 0; k < triangles.size(); ++k)  // increasing k: rows come out sorted
    for (int i = 0; i < 3; ++i)
      if (distinct(triangles[k], i)) m_triangles[next[triangles[k][i]]++] = k;
  m_edges.resize(triangles.size());
  m_lowest.assign(triangles.size(), 0);
  for (std::uint32_t k = 0; k < triangles.size(); ++k)
    for (int i = 0; i < 3; ++i) {
      const std::size_t c = std::size_t(i);
      m_edges[k][c] = edge_triangles(
          *this, {triangles[k][std::size_t(i)], triangles[k][std::size_t((i + 1) % 3)]});
      const EdgeTriangles& e = m_edges[k][c];
      const auto bit = [](bool b, int at) { return std::uint16_t(b ? 1u << at : 0u); };
      m_lowest[k] |= bit(around(triangles[k][c]).front() == k, i) |
                     bit(e.count > 0 && e.triangles[0] == k, 3 + i) | bit(!e.complete, 6 + i);
    }
}

bool owns_vertex_face(const OwnerSide& a, std::uint32_t ta, std::uint32_t v, const OwnerSide& b,
                      std::uint32_t tb, bool self) {
  for (std::uint32_t t : a.around->around(v))
    if (may_pair(a, t, tb, self)) return t == ta;
  return false;  // unreachable for a pair that may be paired: ta itself is around v
}

EdgeTriangles edge_triangles(const VertexTriangles& around, std::array<std::uint32_t, 2> edge) {
  EdgeTriangles out;
  const std::span<const std::uint32_t> x = around.around(edge[0]), y = around.around(edge[1]);
  for (std::size_t i = 0, j = 0; i < x.size() && j < y.size();) {
    if (x[i] < y[j]) {
      ++i;
    } else if (y[j] < x[i]) {
      ++j;
    } else {
      if (out.count == out.triangles.size()) {
        out.complete = false;
        break;
      }
      out.triangles[out.count++] = x[i];
      ++i;
      ++j;
    }
  }
  return out;
}

bool owns_edge_edge(const OwnerSide& a, std::uint32_t ta, const EdgeTriangles& ea,
                    const OwnerSide& b, std::uint32_t tb, const EdgeTriangles& eb, bool self) {
  if (!ea.complete || !eb.complete) return true;
  const auto key = [self](std::uint32_t x, std::uint32_t y) {
    return self ? std::pair(std::min(x, y), std::max(x, y)) : std::pair(x, y);
  };
  const std::pair<std::uint32_t, std::uint32_t> mine = key(ta, tb);
  for (std::uint32_t i = 0; i < ea.count; ++i)
    for (std::uint32_t j = 0; j < eb.count; ++j) {
      const std::uint32_t x = ea.triangles[i], y = eb.triangles[j];
      if (key(x, y) < mine && may_pair(a, x, y, self)) return false;
    }
  return true;
}

OwnedPrimitives owned_primitives(const OwnerSide& a, std::uint32_t ta, const OwnerSide& b,
                                 std::uint32_t tb, bool self) {
  OwnedPrimitives owned = 0;
  if (!self) {
    // Every pair may be paired: a vertex's owner is the lowest triangle around it, an edge
    // pair's the pair of the lowest triangles of each edge (the lowest pair), or every pair when
    // a list is incomplete; the ranks are kept per triangle.
    const unsigned la = a.around->lowest(ta), lb = b.around->lowest(tb);
    for (int i = 0; i < 3; ++i) {
      owned |= OwnedPrimitives(((la >> i) & 1u) << (2 * i));
      owned |= OwnedPrimitives(((lb >> i) & 1u) << (2 * i + 1));
    }
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) {
        const bool incomplete = ((la >> (6 + i)) & 1u) != 0 || ((lb >> (6 + j)) & 1u) != 0;
        const bool lowest = ((la >> (3 + i)) & 1u) != 0 && ((lb >> (3 + j)) & 1u) != 0;
        if (incomplete || lowest) owned |= OwnedPrimitives(1u << (6 + 3 * i + j));
      }
    return owned;
  }
  const std::array<std::uint32_t, 3>& fa = a.triangles[ta];
  const std::array<std::uint32_t, 3>& fb = b.triangles[tb];
  for (int i = 0; i < 3; ++i) {
    if (owns_vertex_face(a, ta, fa[i], b, tb, self)) owned |= OwnedPrimitives(1u << (2 * i));
    if (owns_vertex_face(b, tb, fb[i], a, ta, self)) owned |= OwnedPrimitives(1u << (2 * i + 1));
  }
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      if (owns_edge_edge(a, ta, a.around->edge(ta, i), b, tb, b.around->edge(tb, j), self))
        owned |= OwnedPrimitives(1u << (6 + 3 * i + j));
  return owned;
}

}  // namespace kinray
