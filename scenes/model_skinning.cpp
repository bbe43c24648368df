#include "scenes/model_skinning.h"

#include <assimp/mesh.h>

#include <cmath>

#include "util/input_error.h"

namespace kinray {

Skin read_skin(const aiMesh& mesh, const NodeGraph& graph, const std::string& where) {
  Skin skin;
  if (mesh.mNumBones == 0 || mesh.mBones == nullptr) return skin;
  const size_t nv = mesh.mNumVertices;
  std::vector<std::vector<std::pair<uint32_t, double>>> influences(nv);
  for (unsigned b = 0; b < mesh.mNumBones; ++b) {
    const aiBone* bone = mesh.mBones[b];
    if (bone == nullptr) throw InputError(where, "bone " + std::to_string(b) + " is missing");
    const std::string name = bone->mName.C_Str();
    const std::string bone_where = where + " bone '" + name + "'";
    const int node = graph.find(name);
    if (node < 0)
      warn_repair(bone_where,
                  "has no node of that name in the hierarchy; it keeps its bind pose (its share of "
                  "each vertex follows the mesh's node)");
    const Mat4 offset = to_eigen(bone->mOffsetMatrix);
    if (!offset.allFinite()) throw InputError(bone_where, "has a NaN or infinite offset matrix");
    if (bone->mNumWeights > 0 && bone->mWeights == nullptr)
      throw InputError(bone_where, "has a weight count but no weights");
    for (unsigned w = 0; w < bone->mNumWeights; ++w) {
      const aiVertexWeight& weight = bone->mWeights[w];
      if (weight.mVertexId >= nv)
        throw InputError(bone_where, "weighs vertex " + std::to_string(weight.mVertexId) +
                                         ", but the mesh has " + std::to_string(nv) + " vertices");
      if (!std::isfinite(weight.mWeight) || weight.mWeight < 0)
        throw InputError(bone_where, "has a negative, NaN or infinite weight on vertex " +
                                         std::to_string(weight.mVertexId));
      if (weight.mWeight > 0) influences[weight.mVertexId].emplace_back(b, double(weight.mWeight));
    }
    skin.bone_nodes.push_back(node);
    skin.offsets.push_back(offset);
  }
  size_t off_by_more = 0;
  skin.first.reserve(nv + 1);
  skin.first.push_back(0);
  for (size_t v = 0; v < nv; ++v) {
    double sum = 0;
    for (const auto& [bone, weight] : influences[v]) sum += weight;
    if (sum > 0 && std::abs(sum - 1.0) > 0.01) ++off_by_more;
    for (const auto& [bone, weight] : influences[v]) {
      skin.bones.push_back(bone);
      skin.weights.push_back(weight / sum);
    }
    skin.first.push_back(uint32_t(skin.bones.size()));
  }
  if (off_by_more > 0)
    warn_repair(where, "the bone weights of " + std::to_string(off_by_more) +
                           " vertices do not sum to 1; normalized them");
  return skin;
}

void apply_skin(const Skin& skin, std::span<const Vec3> positions, std::span<const Mat4> globals,
                const Mat4& mesh_node, std::span<Vec3> out) {
  std::vector<Mat4> bone_matrices(skin.bone_nodes.size());
  for (size_t b = 0; b < bone_matrices.size(); ++b)
    bone_matrices[b] = skin.bone_nodes[b] < 0
                           ? mesh_node
                           : Mat4(globals[size_t(skin.bone_nodes[b])] * skin.offsets[b]);
  for (size_t v = 0; v < positions.size(); ++v) {
    const uint32_t begin = skin.first[v], end = skin.first[v + 1];
    if (begin == end) {
      out[v] = transform_point(mesh_node, positions[v]);
      continue;
    }
    Vec3 sum = Vec3::Zero();
    for (uint32_t i = begin; i < end; ++i)
      sum += skin.weights[i] * transform_point(bone_matrices[skin.bones[i]], positions[v]);
    out[v] = sum;
  }
}

}  // namespace kinray
