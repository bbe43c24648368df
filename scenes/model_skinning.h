#pragma once
// Skeletal skinning (linear blend): a skinned vertex is sum_b w_b * G_b * O_b * v, with G_b the
// global transform of bone b's node at time t and O_b its offset matrix (aiBone::mOffsetMatrix,
// mesh space to bone space in the bind pose). The result is already in world space: the mesh
// node's own global transform cancels out (O_b holds its inverse), as in glTF and in assimp's
// viewer. Vertices no bone weighs follow the mesh node rigidly.
#include <span>
#include <string>
#include <vector>

#include "scenes/model_animation.h"

struct aiMesh;

namespace kinray {

/// The bones of one mesh and, per vertex, the bones that weigh it (weights summing to 1).
struct Skin {
  std::vector<int> bone_nodes;  ///< node of each bone, index into NodeGraph::nodes, or -1
  std::vector<Mat4> offsets;    ///< aiBone::mOffsetMatrix of each bone
  std::vector<uint32_t> first;  ///< influences of vertex v: [first[v], first[v + 1])
  std::vector<uint32_t> bones;  ///< bone of each influence
  std::vector<double> weights;  ///< weight of each influence
  [[nodiscard]] bool empty() const { return bone_nodes.empty(); }
};

/// Reads the bones of `mesh`. Throws InputError (at `where`) for a weight on a vertex out of range,
/// a negative, NaN or infinite weight, or a bad offset matrix. Repairs, with a warning: a bone
/// whose node is missing keeps its bind pose (G_b * O_b is the mesh node's transform); weights
/// that do not sum to 1 are normalized (warned when they are off by more than 1%).
[[nodiscard]] Skin read_skin(const aiMesh& mesh, const NodeGraph& graph, const std::string& where);

/// World positions of the skinned vertices: `globals` are the node transforms at the time,
/// `mesh_node` the global transform of the node that instances the mesh.
void apply_skin(const Skin& skin, std::span<const Vec3> positions, std::span<const Mat4> globals,
                const Mat4& mesh_node, std::span<Vec3> out);

}  // namespace kinray
