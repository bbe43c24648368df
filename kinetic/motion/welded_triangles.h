#pragma once
// Seams welded. Exporters of skinned models split a mesh edge where texture coordinates or
// normals change: the seam's two sides use different vertices that move as one, having the same
// position at every key. Welded, the two sides share their edge: the kinetic grid tracks it once
// and orders its sides by their fold, and collision detection treats them as the neighbours they
// are instead of as two triangles in contact along the seam all the time.
#include <array>
#include <cstdint>
#include <vector>

#include "kinetic/motion/flightplan_mesh.h"

namespace kinray {

/// The mesh's triangles (its own vertex ids) with each vertex replaced by the lowest vertex of
/// the mesh with the same flightplan. A triangle that welding would give one vertex twice (it
/// never has an area) keeps its ids. Every position read through a welded id is the one read
/// through the input's.
[[nodiscard]] std::vector<std::array<uint32_t, 3>> welded_triangles(const FlightplanMesh& mesh);

}  // namespace kinray
