#pragma once
// The kinds of the per-square sets' events, in the order equal times are processed: a mesh's key
// and presence first (they rebuild whole meshes, and a certificate of the old key segment may
// fail at the key itself), then a triangle's own rebuilds, then the local moves.
#include <cstddef>
#include <cstdint>

namespace kinray {

inline constexpr uint32_t kSquareKey = 0;          ///< a = mesh
inline constexpr uint32_t kSquarePresence = 1;     ///< a = mesh
inline constexpr uint32_t kSquareOrientation = 2;  ///< a = triangle
inline constexpr uint32_t kSquareHorizon = 3;      ///< a = triangle, b = its edge (n_x = 0)
inline constexpr uint32_t kSquareVertex = 4;       ///< a = global vertex
inline constexpr uint32_t kSquareCorner = 5;       ///< a = straddling triangle, b = its line entry
inline constexpr uint32_t kSquareEdgeCorner = 6;   ///< a = edge, b = its line's index

/// The payload of a triangle's or an edge's event: its id and which of its certificates (the edge
/// for kSquareHorizon, the line entry for kSquareCorner, the line for kSquareEdgeCorner).
[[nodiscard]] inline uint64_t square_event_payload(uint32_t tri, size_t sub) {
  return (uint64_t(tri) << 32) | uint64_t(sub);
}

}  // namespace kinray
