#include "scenes/model_animation.h"

#include <assimp/anim.h>
#include <assimp/scene.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <sstream>
#include <unordered_set>

#include "util/input_error.h"

namespace kinray {

namespace {

Extrapolation extrapolation(aiAnimBehaviour behaviour) {
  switch (behaviour) {
    case aiAnimBehaviour_LINEAR:
      return Extrapolation::linear;
    case aiAnimBehaviour_REPEAT:
      return Extrapolation::repeat;
    default:
      return Extrapolation::hold;  // DEFAULT and CONSTANT: see Extrapolation
  }
}

Vec3 interpolate(const Vec3& a, const Vec3& b, double alpha) {
  return a + alpha * (b - a);
}
Eigen::Quaterniond interpolate(const Eigen::Quaterniond& a, const Eigen::Quaterniond& b,
                               double alpha) {
  return a.slerp(alpha, b);  // Eigen takes the shorter arc, as assimp's aiQuaternion::Interpolate
}

template <class Value>
Value sample_track(const Track<Value>& track, double ticks) {
  const std::vector<double>& times = track.times;
  const size_t n = times.size();
  if (n == 1) return track.values[0];
  const double first = times.front(), last = times.back();
  auto wrap = [&](double t) {
    return first + std::fmod(std::fmod(t - first, last - first) + (last - first), last - first);
  };
  if (ticks < first) {
    if (track.before == Extrapolation::hold) return track.values.front();
    if (track.before == Extrapolation::linear)
      return interpolate(track.values[0], track.values[1],
                         (ticks - times[0]) / (times[1] - times[0]));
    ticks = wrap(ticks);
  } else if (ticks > last) {
    if (track.after == Extrapolation::hold) return track.values.back();
    if (track.after == Extrapolation::linear)
      return interpolate(track.values[n - 2], track.values[n - 1],
                         (ticks - times[n - 2]) / (times[n - 1] - times[n - 2]));
    ticks = wrap(ticks);
  }
  if (ticks >= last) return track.values.back();
  if (ticks <= first) return track.values.front();
  const size_t k = size_t(std::upper_bound(times.begin(), times.end(), ticks) - times.begin()) - 1;
  return interpolate(track.values[k], track.values[k + 1],
                     (ticks - times[k]) / (times[k + 1] - times[k]));
}

template <class Key, class Value, class Convert>
Track<Value> read_track(const Key* keys, unsigned count, const aiNodeAnim& channel,
                        const std::string& where, Convert convert) {
  Track<Value> track;
  track.before = extrapolation(channel.mPreState);
  track.after = extrapolation(channel.mPostState);
  if (count > 0 && keys == nullptr) throw InputError(where, "has a key count but no keys");
  for (unsigned k = 0; k < count; ++k) {
    track.times.push_back(keys[k].mTime);
    track.values.push_back(convert(keys[k].mValue, k));
  }
  clean_keys(track.times, track.values, where);
  return track;
}

}  // namespace

Vec3 sample(const VectorTrack& track, double ticks) {
  return sample_track(track, ticks);
}
Eigen::Quaterniond sample(const RotationTrack& track, double ticks) {
  return sample_track(track, ticks);
}

template <class Value>
void clean_keys(std::vector<double>& times, std::vector<Value>& values, const std::string& where) {
  for (size_t k = 0; k < times.size(); ++k)
    if (!std::isfinite(times[k]))
      throw InputError(where, "key " + std::to_string(k) + " has a NaN or infinite time");
  if (!std::is_sorted(times.begin(), times.end())) {
    std::vector<size_t> order(times.size());
    std::iota(order.begin(), order.end(), size_t(0));
    std::stable_sort(order.begin(), order.end(),
                     [&](size_t a, size_t b) { return times[a] < times[b]; });
    std::vector<double> sorted_times;
    std::vector<Value> sorted_values;
    for (size_t i : order) {
      sorted_times.push_back(times[i]);
      sorted_values.push_back(values[i]);
    }
    times = std::move(sorted_times);
    values = std::move(sorted_values);
    warn_repair(where, "keys were not in time order; sorted them");
  }
  size_t kept = 0, duplicates = 0;
  for (size_t k = 0; k < times.size(); ++k) {
    if (kept > 0 && times[k] == times[kept - 1]) {
      ++duplicates;
      --kept;  // the later of two keys at one time wins: a flightplan cannot jump
    }
    times[kept] = times[k];
    values[kept] = values[k];
    ++kept;
  }
  times.resize(kept);
  values.resize(kept);
  if (duplicates > 0)
    warn_repair(where, std::to_string(duplicates) +
                           " key(s) repeated an earlier key's time; kept the last of each");
}

template void clean_keys(std::vector<double>&, std::vector<Vec3>&, const std::string&);
template void clean_keys(std::vector<double>&, std::vector<Eigen::Quaterniond>&,
                         const std::string&);
template void clean_keys(std::vector<double>&, std::vector<std::vector<double>>&,
                         const std::string&);

NodeChannel read_node_channel(const aiNodeAnim& channel, const std::string& where) {
  auto vector = [&](const std::string& what) {
    return [&, what](const aiVector3D& v, unsigned k) {
      const Vec3 value = to_eigen(v);
      if (!value.allFinite())
        throw InputError(where, what + " key " + std::to_string(k) + " is NaN or infinite");
      return value;
    };
  };
  auto rotation = [&](const aiQuaternion& q, unsigned k) {
    const Eigen::Quaterniond value = to_eigen(q);
    const double norm = value.norm();
    if (!std::isfinite(norm) || norm < 1e-12)
      throw InputError(where, "rotation key " + std::to_string(k) +
                                  " is not a rotation (NaN, infinite or zero quaternion)");
    return value.normalized();
  };
  NodeChannel result;
  result.translation =
      read_track<aiVectorKey, Vec3>(channel.mPositionKeys, channel.mNumPositionKeys, channel,
                                    where + " position keys", vector("position"));
  result.rotation = read_track<aiQuatKey, Eigen::Quaterniond>(
      channel.mRotationKeys, channel.mNumRotationKeys, channel, where + " rotation keys", rotation);
  result.scaling =
      read_track<aiVectorKey, Vec3>(channel.mScalingKeys, channel.mNumScalingKeys, channel,
                                    where + " scaling keys", vector("scaling"));
  return result;
}

int NodeGraph::find(const std::string& name) const {
  const auto it = by_name.find(name);
  return it == by_name.end() ? -1 : it->second;
}

void NodeGraph::global_transforms(double ticks, std::vector<Mat4>& out) const {
  out.resize(nodes.size());
  for (size_t n = 0; n < nodes.size(); ++n) {
    Mat4 local = rest[n];
    if (channel_of[n] >= 0) {
      const NodeChannel& channel = channels[size_t(channel_of[n])];
      // An empty track keeps that part of the rest transform (decomposed as T * R * S).
      const Eigen::Matrix3d linear = rest[n].topLeftCorner<3, 3>();
      Vec3 rest_scale(linear.col(0).norm(), linear.col(1).norm(), linear.col(2).norm());
      Vec3 translation = channel.translation.empty() ? Vec3(rest[n].topRightCorner<3, 1>())
                                                     : sample(channel.translation, ticks);
      Vec3 scale = channel.scaling.empty() ? rest_scale : sample(channel.scaling, ticks);
      Eigen::Quaterniond rotation;
      if (channel.rotation.empty()) {
        Eigen::Matrix3d unscaled = linear;
        for (int c = 0; c < 3; ++c)
          if (rest_scale[c] > 0) unscaled.col(c) /= rest_scale[c];
        if (unscaled.determinant() < 0) {  // a mirroring rest transform: keep the sign in the scale
          unscaled.col(0) *= -1;
          rest_scale[0] *= -1;
          if (channel.scaling.empty()) scale = rest_scale;
        }
        rotation = Eigen::Quaterniond(unscaled).normalized();
      } else {
        rotation = sample(channel.rotation, ticks);
      }
      local.setIdentity();
      local.topLeftCorner<3, 3>() = rotation.toRotationMatrix() * scale.asDiagonal();
      local.topRightCorner<3, 1>() = translation;
    }
    out[n] = parents[n] < 0 ? local : Mat4(out[size_t(parents[n])] * local);
  }
}

bool NodeGraph::moves(int n) const {
  for (; n >= 0; n = parents[size_t(n)])
    if (channel_of[size_t(n)] >= 0) return true;
  return false;
}

std::vector<double> NodeGraph::key_ticks() const {
  std::vector<double> ticks;
  for (const NodeChannel& channel : channels) {
    ticks.insert(ticks.end(), channel.translation.times.begin(), channel.translation.times.end());
    ticks.insert(ticks.end(), channel.rotation.times.begin(), channel.rotation.times.end());
    ticks.insert(ticks.end(), channel.scaling.times.begin(), channel.scaling.times.end());
  }
  return ticks;
}

NodeGraph build_node_graph(const aiScene& scene, const aiAnimation* animation,
                           const std::string& where) {
  NodeGraph graph;
  if (scene.mRootNode == nullptr) throw InputError(where, "has no node hierarchy");
  // Iterative depth-first walk: a hostile file may nest nodes deeper than the call stack allows.
  std::vector<std::pair<const aiNode*, int>> stack = {{scene.mRootNode, -1}};
  std::unordered_set<const aiNode*> seen;
  while (!stack.empty()) {
    const auto [node, parent] = stack.back();
    stack.pop_back();
    if (node == nullptr) throw InputError(where, "has an empty node in its hierarchy");
    if (!seen.insert(node).second) throw InputError(where, "has a cycle in its node hierarchy");
    const int index = int(graph.nodes.size());
    graph.nodes.push_back(node);
    graph.parents.push_back(parent);
    graph.rest.push_back(to_eigen(node->mTransformation));
    if (!graph.rest.back().allFinite())
      throw InputError(where, "node '" + std::string(node->mName.C_Str()) +
                                  "' has a NaN or infinite transformation");
    graph.channel_of.push_back(-1);
    graph.by_name.emplace(node->mName.C_Str(), index);
    for (unsigned c = node->mNumChildren; c-- > 0;) stack.emplace_back(node->mChildren[c], index);
  }
  if (animation == nullptr) return graph;
  const std::string animation_where = where + ": animation '" + animation->mName.C_Str() + "'";
  for (unsigned c = 0; c < animation->mNumChannels; ++c) {
    const aiNodeAnim* channel = animation->mChannels[c];
    if (channel == nullptr) continue;
    const std::string name = channel->mNodeName.C_Str();
    const std::string channel_where = animation_where + " channel '" + name + "'";
    const int node = graph.find(name);
    if (node < 0) {
      warn_repair(channel_where, "animates a node that does not exist; ignored");
      continue;
    }
    NodeChannel cleaned = read_node_channel(*channel, channel_where);
    if (graph.channel_of[size_t(node)] >= 0) {
      warn_repair(channel_where,
                  "animates a node that an earlier channel already animates; ignored");
      continue;
    }
    graph.channel_of[size_t(node)] = int(graph.channels.size());
    graph.channels.push_back(std::move(cleaned));
  }
  return graph;
}

AnimationClip select_animation(const aiScene& scene, const std::string& request,
                               const std::string& source) {
  AnimationClip clip;
  if (scene.mNumAnimations == 0 || scene.mAnimations == nullptr) {
    if (!request.empty())
      throw InputError(source, "has no animations, but animation '" + request + "' was asked for");
    return clip;
  }
  auto name_of = [&](size_t i) { return std::string(scene.mAnimations[i]->mName.C_Str()); };
  size_t chosen = scene.mNumAnimations;
  if (request.empty()) {
    chosen = 0;
  } else if (std::all_of(request.begin(), request.end(),
                         [](char c) { return c >= '0' && c <= '9'; }) &&
             request.size() < 10) {
    chosen = size_t(std::stoul(request));
  } else {
    for (size_t i = 0; i < scene.mNumAnimations && chosen == scene.mNumAnimations; ++i)
      if (name_of(i) == request) chosen = i;
  }
  if (chosen >= scene.mNumAnimations) {
    std::ostringstream list;
    for (size_t i = 0; i < scene.mNumAnimations; ++i)
      list << (i ? ", " : "") << i << " '" << name_of(i) << "'";
    throw InputError(source, "unknown animation '" + request + "'; available: " + list.str());
  }
  const aiAnimation& animation = *scene.mAnimations[chosen];
  clip.animation = &animation;
  clip.index = chosen;
  clip.name = name_of(chosen);
  if (!std::isfinite(animation.mTicksPerSecond) || animation.mTicksPerSecond < 0)
    throw InputError(source + ": animation '" + clip.name + "'",
                     "has an invalid tick rate " + std::to_string(animation.mTicksPerSecond));
  clip.ticks_per_second = animation.mTicksPerSecond > 0 ? animation.mTicksPerSecond : 25.0;
  return clip;
}

void merge_key_times(std::vector<double>& times) {
  std::sort(times.begin(), times.end());
  if (times.empty()) return;
  const double tolerance =
      1e-6 * std::max(1.0, std::max(std::abs(times.front()), std::abs(times.back())));
  size_t kept = 1;
  for (size_t k = 1; k < times.size(); ++k)
    if (times[k] - times[kept - 1] > tolerance) times[kept++] = times[k];
  times.resize(kept);
}

}  // namespace kinray
