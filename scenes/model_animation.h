#pragma once
// Node animation of an assimp scene evaluated at any time: each animated node's translation
// (lerp), rotation (slerp) and scaling (lerp) keys, with the pre- and post-state behaviour of
// aiNodeAnim, composed down the node hierarchy into global (model-to-world) transforms.
#include <string>
#include <unordered_map>
#include <vector>

#include "scenes/model_assimp.h"

struct aiAnimation;
struct aiNode;
struct aiNodeAnim;
struct aiScene;

namespace kinray {

/// What a track does outside its keys (aiAnimBehaviour). assimp's DEFAULT ("the node's own
/// transformation") is what nearly every importer leaves in place, while the formats themselves
/// (glTF, FBX, COLLADA, X, BVH, MD5) clamp; DEFAULT therefore holds the nearest key like CONSTANT.
enum class Extrapolation { hold, linear, repeat };

/// Keys of one quantity, in ticks, strictly increasing (see clean_keys).
template <class Value>
struct Track {
  std::vector<double> times;
  std::vector<Value> values;
  Extrapolation before = Extrapolation::hold;
  Extrapolation after = Extrapolation::hold;
  [[nodiscard]] bool empty() const { return times.empty(); }
};
using VectorTrack = Track<Vec3>;
using RotationTrack = Track<Eigen::Quaterniond>;

/// Value of a track at `ticks`: linear between keys (slerp for rotations), extrapolated outside
/// them by `before` / `after`. The track must not be empty.
[[nodiscard]] Vec3 sample(const VectorTrack& track, double ticks);
[[nodiscard]] Eigen::Quaterniond sample(const RotationTrack& track, double ticks);

/// Repairs a key list in place: throws InputError (at `where`) on a NaN or infinite time;
/// sorts unsorted keys and keeps the last of keys with equal times, with a warning each.
template <class Value>
void clean_keys(std::vector<double>& times, std::vector<Value>& values, const std::string& where);

/// The animation of one node (an aiNodeAnim, cleaned). An empty track keeps the node's rest value.
struct NodeChannel {
  VectorTrack translation;
  RotationTrack rotation;
  VectorTrack scaling;
};

/// Reads and cleans an aiNodeAnim; throws InputError on NaN or infinite key values and on a zero
/// rotation quaternion.
[[nodiscard]] NodeChannel read_node_channel(const aiNodeAnim& channel, const std::string& where);

/// The node hierarchy, flattened so that parents come before children (depth-first, the order
/// of aiNode::FindNode), with the chosen animation's channels attached.
struct NodeGraph {
  std::vector<const aiNode*> nodes;
  std::vector<int> parents;     ///< -1 for the root
  std::vector<Mat4> rest;       ///< aiNode::mTransformation
  std::vector<int> channel_of;  ///< index into channels, or -1
  std::vector<NodeChannel> channels;
  std::unordered_map<std::string, int> by_name;  ///< the first node of each name

  /// Index of the first node called `name`, or -1.
  [[nodiscard]] int find(const std::string& name) const;
  /// Global transforms of all nodes at `ticks`, into `out` (resized).
  void global_transforms(double ticks, std::vector<Mat4>& out) const;
  /// True when node n or one of its ancestors is animated.
  [[nodiscard]] bool moves(int n) const;
  /// Every key time of every channel, in ticks, unsorted.
  [[nodiscard]] std::vector<double> key_ticks() const;
};

/// Builds the hierarchy of `scene` with the channels of `animation` (may be null). Channels for
/// nodes that do not exist are skipped with a warning. Throws InputError (at `where`) on bad keys.
[[nodiscard]] NodeGraph build_node_graph(const aiScene& scene, const aiAnimation* animation,
                                         const std::string& where);

/// The animation a model is shown with.
struct AnimationClip {
  const aiAnimation* animation = nullptr;  ///< null: the model is static
  size_t index = 0;
  std::string name;
  double ticks_per_second = 25;  ///< aiAnimation::mTicksPerSecond, with assimp's 0 meaning 25
};

/// Picks the animation named, or numbered, by `request` (empty: the first, or none when the model
/// has none). Throws InputError (at `source`) for an unknown request, listing the available ones,
/// and for a negative or non-finite tick rate.
[[nodiscard]] AnimationClip select_animation(const aiScene& scene, const std::string& request,
                                             const std::string& source);

/// Sorts `times` and merges times closer than 1e-6 of their magnitude (keys of different channels
/// that stand for the same frame but were rounded differently, e.g. through float seconds).
void merge_key_times(std::vector<double>& times);

}  // namespace kinray
