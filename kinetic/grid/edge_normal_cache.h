#pragma once
// The edge normals p x q (triangle_motion.h) of a band's mesh edges on their meshes' current
// segments, computed once per edge and segment instead of once per use: a boundary event tests
// the edge functions of its own edge and of the two records' other edges, and each was rebuilt
// from the vertex motions every time (three cross products of polynomials, about 6% of an
// event's instructions). The cached normal is the same function of the same motions, so every
// sign and certificate built from it is bit for bit the one built before; the normal of a
// triangle's edge taken against the edge's own direction is its exact negation
// (EdgeNormal::reversed).
//
// Each band keeps a table by edge of the scene, but meets only the edges near its rows, and a
// thread runs several bands: the normals' storage is left unwritten until a normal is built, so
// the pages of edges a band never meets are never touched and take no memory (1,000,000
// triangles, one thread, four bands: peak resident memory 2.41 -> 2.04 GB). A normal is read only
// once its stamp says it was built; the stamps (4 bytes an edge) are zeroed. memory_bytes counts
// the pages written (by offset from the table's start, which is near enough to the pages).
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <new>
#include <utility>
#include <vector>

#include "kinetic/motion/triangle_motion.h"

namespace kinray {

class EdgeNormalCache {
 public:
  explicit EdgeNormalCache(size_t edge_count)
      : m_normals(std::make_unique_for_overwrite<Storage[]>(edge_count)),
        m_stamps(edge_count, 0),
        m_page_written(edge_count * sizeof(Storage) / kPage + 2, false) {}

  /// The normal of edge `edge` from p to q (its own direction), built on first use after the
  /// last invalidate().
  [[nodiscard]] const EdgeNormal& get(uint32_t edge, const PointMotion& p, const PointMotion& q) {
    return get_lazily(edge, [&] { return std::pair{&p, &q}; });
  }
  /// The same, with the end points' motions asked for only when the normal is built
  /// (`ends()` returns pointers to p and q): a hit reads the stamp and the normal alone, not the
  /// edge's end points, a third random line of a boundary event.
  template <class Ends>
  [[nodiscard]] const EdgeNormal& get_lazily(uint32_t edge, Ends&& ends) {
    if (m_stamps[edge] != m_generation) [[unlikely]] {
      const auto [p, q] = ends();
      build(edge, *p, *q);
    }
    return normal(edge);
  }
  /// Starts fetching what get() of the edge reads (a software prefetch).
  void prefetch(uint32_t edge) const {
    __builtin_prefetch(&m_stamps[edge]);
    const std::byte* bytes = m_normals[edge].bytes;
    __builtin_prefetch(bytes);
    __builtin_prefetch(bytes + sizeof(EdgeNormal) - 1);
  }
  /// Forgets every normal (some vertex motions changed).
  void invalidate() {
    if (++m_generation == 0) {  // wrapped: no stale stamp may match
      std::fill(m_stamps.begin(), m_stamps.end(), 0);
      m_generation = 1;
    }
  }
  /// The stamps, and the normals' pages written so far (the table's pages of edges never met
  /// take no memory).
  [[nodiscard]] size_t memory_bytes() const {
    return m_pages_written * kPage + m_stamps.capacity() * sizeof(uint32_t) +
           (m_page_written.capacity() + 7) / 8;  // one bit a page
  }

 private:
  /// The miss (once per edge and segment), out of line: the callers' fast paths stay small.
  [[gnu::noinline]] void build(uint32_t edge, const PointMotion& p, const PointMotion& q) {
    ::new (static_cast<void*>(m_normals[edge].bytes)) EdgeNormal(edge_normal(p, q));
    m_stamps[edge] = m_generation;
    const size_t first = size_t(edge) * sizeof(Storage);
    for (size_t page : {first / kPage, (first + sizeof(Storage) - 1) / kPage})
      if (!m_page_written[page]) {
        m_page_written[page] = true;
        ++m_pages_written;
      }
  }
  static constexpr size_t kPage = 4096;
  /// Room for one normal, not written until it is built (EdgeNormal's own constructor would
  /// write every page of the table).
  struct Storage {
    alignas(EdgeNormal) std::byte bytes[sizeof(EdgeNormal)];
  };
  [[nodiscard]] const EdgeNormal& normal(uint32_t edge) const {
    return *std::launder(reinterpret_cast<const EdgeNormal*>(m_normals[edge].bytes));
  }
  std::unique_ptr<Storage[]> m_normals;  ///< by edge; the ones stamped with a generation built
  std::vector<uint32_t> m_stamps;  ///< the generation each normal was built in
  uint32_t m_generation = 1;
  std::vector<bool> m_page_written;  ///< by page of m_normals (offsets from its start)
  size_t m_pages_written = 0;
};

}  // namespace kinray
