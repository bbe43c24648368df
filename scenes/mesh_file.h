#pragma once
// What the mesh-sequence readers (ply_reader.h, obj_reader.h) return for one file: its meshes,
// each with its own vertices in full double precision (simulators write doubles; assimp's floats
// would move their contacts) and triangles, polygons fanned. Shared checks of the readers live
// here so that PLY and OBJ refuse the same things the same way.
#include <string>
#include <string_view>
#include <vector>

#include "scenes/scene.h"

namespace kinray {

/// One mesh of a file: an OBJ object or group, or a PLY file's whole mesh.
struct MeshPart {
  std::string name;             ///< the OBJ object/group name; empty for PLY and unnamed OBJ
  std::vector<Vec3> positions;  ///< in the part's own numbering
  std::vector<Triangle> triangles;
};

/// The meshes of one file, in the order they first appear.
struct MeshFile {
  std::vector<MeshPart> parts;
};

/// Throws InputError at `where` unless `value` is finite and within +-kMaxCoordinate (the bound
/// Scene::validate holds every scene to), naming `what` ("x").
void check_mesh_coordinate(double value, const char* what, const std::string& where);

/// The whole of the file at `path` as bytes; throws InputError naming it when it cannot be read.
[[nodiscard]] std::string read_mesh_bytes(const std::string& path);

/// The words of one line, split at spaces, tabs, CR, FF and VT.
[[nodiscard]] std::vector<std::string_view> split_words(std::string_view line);

/// Appends the fan (p0, pk, pk+1) of a polygon with at least three corners.
void append_fan(const std::vector<uint32_t>& polygon, std::vector<Triangle>& triangles);

}  // namespace kinray
