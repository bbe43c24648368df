#include "scenes/model_morph.h"

#include <assimp/anim.h>
#include <assimp/mesh.h>

#include <algorithm>
#include <cmath>

#include "scenes/model_animation.h"
#include "util/input_error.h"

namespace kinray {

MorphTargets read_morph_targets(const aiMesh& mesh, const std::string& where) {
  MorphTargets targets;
  if (mesh.mNumAnimMeshes == 0 || mesh.mAnimMeshes == nullptr) return targets;
  const bool relative = mesh.mMethod == aiMorphingMethod_MORPH_RELATIVE;
  for (unsigned i = 0; i < mesh.mNumAnimMeshes; ++i) {
    const aiAnimMesh* target = mesh.mAnimMeshes[i];
    const std::string target_where = where + " morph target " + std::to_string(i);
    std::vector<Vec3> displacement(mesh.mNumVertices, Vec3::Zero());
    if (target != nullptr && target->mVertices != nullptr) {
      if (target->mNumVertices != mesh.mNumVertices)
        throw InputError(target_where, "has " + std::to_string(target->mNumVertices) +
                                           " vertices, the mesh has " +
                                           std::to_string(mesh.mNumVertices));
      for (unsigned v = 0; v < mesh.mNumVertices; ++v) {
        const Vec3 position = to_eigen(target->mVertices[v]);
        if (!position.allFinite()) throw InputError(target_where, non_finite_vertex(v));
        displacement[v] = relative ? position : Vec3(position - to_eigen(mesh.mVertices[v]));
      }
    }
    const double weight = target != nullptr ? double(target->mWeight) : 0.0;
    if (!std::isfinite(weight)) throw InputError(target_where, "has a NaN or infinite weight");
    targets.displacements.push_back(std::move(displacement));
    targets.default_weights.push_back(weight);
  }
  return targets;
}

MorphWeightTrack read_morph_track(const aiMeshMorphAnim& animation, size_t target_count,
                                  const std::string& where) {
  MorphWeightTrack track;
  if (animation.mNumKeys > 0 && animation.mKeys == nullptr)
    throw InputError(where, "has a key count but no keys");
  for (unsigned k = 0; k < animation.mNumKeys; ++k) {
    const aiMeshMorphKey& key = animation.mKeys[k];
    std::vector<double> weights(target_count, 0.0);
    if (key.mNumValuesAndWeights > 0 && (key.mValues == nullptr || key.mWeights == nullptr))
      throw InputError(where, "key " + std::to_string(k) + " has a weight count but no weights");
    for (unsigned j = 0; j < key.mNumValuesAndWeights; ++j) {
      if (key.mValues[j] >= target_count)
        throw InputError(where, "key " + std::to_string(k) + " weighs morph target " +
                                    std::to_string(key.mValues[j]) + ", but the mesh has " +
                                    std::to_string(target_count));
      if (!std::isfinite(key.mWeights[j]))
        throw InputError(where, "key " + std::to_string(k) + " has a NaN or infinite weight");
      weights[key.mValues[j]] = key.mWeights[j];
    }
    track.times.push_back(key.mTime);
    track.weights.push_back(std::move(weights));
  }
  clean_keys(track.times, track.weights, where);
  return track;
}

std::vector<double> sample(const MorphWeightTrack& track, double ticks) {
  const std::vector<double>& times = track.times;
  if (times.size() == 1 || ticks <= times.front()) return track.weights.front();
  if (ticks >= times.back()) return track.weights.back();
  const size_t k = size_t(std::upper_bound(times.begin(), times.end(), ticks) - times.begin()) - 1;
  const double alpha = (ticks - times[k]) / (times[k + 1] - times[k]);
  std::vector<double> weights(track.weights[k].size());
  for (size_t i = 0; i < weights.size(); ++i)
    weights[i] = track.weights[k][i] + alpha * (track.weights[k + 1][i] - track.weights[k][i]);
  return weights;
}

void apply_morph(std::span<const Vec3> base, const MorphTargets& targets,
                 std::span<const double> weights, std::span<Vec3> out) {
  for (size_t v = 0; v < base.size(); ++v) {
    Vec3 position = base[v];
    for (size_t i = 0; i < targets.displacements.size() && i < weights.size(); ++i)
      if (weights[i] != 0.0) position += weights[i] * targets.displacements[i][v];
    out[v] = position;
  }
}

}  // namespace kinray
