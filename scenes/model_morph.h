#pragma once
// Morph targets (aiAnimMesh) and their animated weights (aiMeshMorphAnim): a morphed vertex is
// base + sum_i w_i * d_i, with d_i the displacement of target i. assimp 5.2 stores glTF, FBX and
// most other targets as absolute positions (base + displacement, aiMesh::mMethod 0 or
// MORPH_NORMALIZED / VERTEX_BLEND), so d_i = target_i - base; a mesh marked MORPH_RELATIVE stores
// the displacements themselves.
#include <span>
#include <string>
#include <vector>

#include "scenes/scene.h"

struct aiMesh;
struct aiMeshMorphAnim;

namespace kinray {

/// The morph targets of one mesh, as displacements from its base positions.
struct MorphTargets {
  std::vector<std::vector<Vec3>> displacements;  ///< [target][vertex]
  std::vector<double> default_weights;           ///< aiAnimMesh::mWeight, used when not animated
  [[nodiscard]] bool empty() const { return displacements.empty(); }
};

/// Reads the targets of `mesh`. Throws InputError (at `where`) when a target's vertex count differs
/// from the mesh's or a position or weight is NaN or infinite.
[[nodiscard]] MorphTargets read_morph_targets(const aiMesh& mesh, const std::string& where);

/// Animated morph weights: at each key (in ticks) one weight per target (targets a key does not
/// name weigh 0). Linear between keys, held outside them.
struct MorphWeightTrack {
  std::vector<double> times;
  std::vector<std::vector<double>> weights;  ///< [key][target]
};

/// Reads and cleans an aiMeshMorphAnim for a mesh with `target_count` targets. Throws InputError
/// (at `where`) on NaN times or weights and on a key naming a target that does not exist.
[[nodiscard]] MorphWeightTrack read_morph_track(const aiMeshMorphAnim& animation,
                                                size_t target_count, const std::string& where);

/// The weights of every target at `ticks`. The track must not be empty.
[[nodiscard]] std::vector<double> sample(const MorphWeightTrack& track, double ticks);

/// out[v] = base[v] + sum_i weights[i] * targets.displacements[i][v] (out may alias base).
void apply_morph(std::span<const Vec3> base, const MorphTargets& targets,
                 std::span<const double> weights, std::span<Vec3> out);

}  // namespace kinray
