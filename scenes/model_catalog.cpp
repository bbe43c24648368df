#include "scenes/model_catalog.h"

#include <assimp/anim.h>
#include <assimp/scene.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace kinray {
namespace {

/// Widens [first, last] by the finite times of `keys`.
template <class Key>
void extend(const Key* keys, unsigned count, double& first, double& last) {
  for (unsigned k = 0; k < count && keys != nullptr; ++k)
    if (std::isfinite(keys[k].mTime)) {
      first = std::min(first, double(keys[k].mTime));
      last = std::max(last, double(keys[k].mTime));
    }
}

AnimationSummary summarize(const aiAnimation& animation, size_t index) {
  AnimationSummary summary;
  summary.index = index;
  summary.name = animation.mName.C_Str();
  if (std::isfinite(animation.mTicksPerSecond) && animation.mTicksPerSecond > 0)
    summary.ticks_per_second = animation.mTicksPerSecond;
  double first = std::numeric_limits<double>::infinity(), last = -first;
  for (unsigned c = 0; c < animation.mNumChannels && animation.mChannels != nullptr; ++c) {
    const aiNodeAnim* channel = animation.mChannels[c];
    if (channel == nullptr) continue;
    ++summary.node_channels;
    extend(channel->mPositionKeys, channel->mNumPositionKeys, first, last);
    extend(channel->mRotationKeys, channel->mNumRotationKeys, first, last);
    extend(channel->mScalingKeys, channel->mNumScalingKeys, first, last);
  }
  for (unsigned c = 0;
       c < animation.mNumMorphMeshChannels && animation.mMorphMeshChannels != nullptr; ++c) {
    const aiMeshMorphAnim* channel = animation.mMorphMeshChannels[c];
    if (channel == nullptr) continue;
    ++summary.morph_channels;
    extend(channel->mKeys, channel->mNumKeys, first, last);
  }
  summary.mesh_channels = animation.mMeshChannels != nullptr ? animation.mNumMeshChannels : 0;
  if (first <= last) {
    summary.first_key = first / summary.ticks_per_second;
    summary.last_key = last / summary.ticks_per_second;
  }
  summary.assimp_duration = animation.mDuration / summary.ticks_per_second;
  return summary;
}

}  // namespace

ModelCatalog model_catalog(const aiScene& scene) {
  ModelCatalog catalog;
  for (unsigned a = 0; a < scene.mNumAnimations && scene.mAnimations != nullptr; ++a)
    if (scene.mAnimations[a] != nullptr)
      catalog.animations.push_back(summarize(*scene.mAnimations[a], a));
  for (unsigned c = 0; c < scene.mNumCameras && scene.mCameras != nullptr; ++c)
    if (scene.mCameras[c] != nullptr) catalog.cameras.push_back(scene.mCameras[c]->mName.C_Str());
  return catalog;
}

}  // namespace kinray
