#pragma once
// A PLY reader that keeps double precision (mesh sequences, docs/mesh_sequences.md): ascii and
// binary little/big endian bodies, any numeric type for the vertex coordinates x, y, z, faces as
// a list property `vertex_indices` (or `vertex_index`) fanned into triangles; other elements and
// properties are read past. Problems are InputErrors at `file:line` (header and ascii body) or
// `file: byte N` (binary body).
#include <string>
#include <string_view>

#include "scenes/mesh_file.h"

namespace kinray {

/// Parses `bytes` as the content of the PLY file `source` (named in errors). The result has one
/// part. Throws InputError for malformed input, NaN/infinite/huge coordinates, indices out of
/// range, faces of fewer than three corners and a mesh without faces.
[[nodiscard]] MeshFile parse_ply(std::string_view bytes, const std::string& source);

/// When the file at `path` is a PLY file (its first line is 'ply'), throws InputError if its
/// header has no end_header line or declares elements without properties (assimp's PLY reader
/// loops without end over either), or if a vertex coordinate is NaN, infinite or beyond
/// +-kMaxCoordinate (assimp takes those as they are). Run before assimp reads a model;
/// everything else about the file is left to assimp.
void check_ply_file(const std::string& path);

/// Reads and parses the file at `path`; throws InputError naming it when it cannot be read.
[[nodiscard]] MeshFile read_ply(const std::string& path);

}  // namespace kinray
