#pragma once
// A Wavefront OBJ reader that keeps double precision (mesh sequences, docs/mesh_sequences.md):
// `v` lines (x y z, optionally w or a colour after them) and `f` lines whose corners take the
// forms i, i/t, i//n and i/t/n with negative indices counting back from the last vertex, polygons
// fanned into triangles. Every `o` or `g` name starts (or resumes) a mesh of its own; everything
// else (vt, vn, usemtl, s, l, ...) is read past. Problems are InputErrors at `file:line`.
#include <string>
#include <string_view>

#include "scenes/mesh_file.h"

namespace kinray {

/// Parses `bytes` as the content of the OBJ file `source` (named in errors). Each part holds the
/// vertices its faces use, numbered in the order of the file (a part whose `v` lines come
/// together keeps the file's numbering, shifted to start at 0); parts without faces are dropped.
/// Throws InputError for malformed lines, NaN/infinite/huge coordinates, indices out of range
/// (or 0), faces of fewer than three corners and a file without faces.
[[nodiscard]] MeshFile parse_obj(std::string_view bytes, const std::string& source);

/// Reads and parses the file at `path`; throws InputError naming it when it cannot be read.
[[nodiscard]] MeshFile read_obj(const std::string& path);

/// When `path` ends in .obj, throws InputError at `file:line` for a `v` line whose x, y or z is
/// NaN, infinite or beyond +-kMaxCoordinate: assimp's OBJ reader takes "nan" as a number and
/// renders the vertex somewhere. Run before assimp reads a model; everything else about the file
/// is left to assimp.
void check_obj_file(const std::string& path);

}  // namespace kinray
