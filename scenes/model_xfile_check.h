#pragma once
// assimp 5.2's DirectX (.x) reader writes out of bounds when a SkinWeights block weighs a vertex
// past its mesh's vertices (XFileImporter::CreateMeshes indexes a per-vertex array with the
// file's index). Whether that crashes depends on the heap, so the reading child of model_guard.h
// cannot be relied on to catch it: text .x files are checked here, before assimp sees them.
#include <string>

namespace kinray {

/// Throws InputError (at `path`) when `path` is a text DirectX file ("xof 0303txt") in which a
/// SkinWeights block names a vertex index not below the vertex count of its mesh, or whose
/// SkinWeights or Mesh counts cannot be read. Other files (binary or compressed .x included, which
/// only the reading child guards) pass untouched.
void check_x_skin_weights(const std::string& path);

}  // namespace kinray
