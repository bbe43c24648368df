#pragma once
// What a model file offers besides the scene it becomes: its animations (name, duration,
// channels) and cameras, for `kinray info`.
#include <string>
#include <vector>

struct aiScene;

namespace kinray {

/// One animation of a model, as `--animation` chooses it.
struct AnimationSummary {
  size_t index = 0;
  std::string name;
  double ticks_per_second = 25;  ///< aiAnimation::mTicksPerSecond, assimp's 0 meaning 25
  /// First and last key time over every node and morph channel, in seconds: the shot `render`
  /// plays (docs/models.md, "Time and keys"); both 0 without keys.
  double first_key = 0, last_key = 0;
  double assimp_duration = 0;  ///< aiAnimation::mDuration in seconds (kinray does not use it)
  size_t node_channels = 0;    ///< aiNodeAnim: node and bone transforms
  size_t morph_channels = 0;   ///< aiMeshMorphAnim: morph target weights
  size_t mesh_channels = 0;    ///< aiMeshAnim: vertex animation, not supported (ignored)
  [[nodiscard]] double duration() const { return last_key - first_key; }
};

struct ModelCatalog {
  std::string file;  ///< the model file; empty: nothing was filled in
  std::vector<AnimationSummary> animations;
  size_t played = 0;                 ///< the animation the scene was loaded with
  std::vector<std::string> cameras;  ///< names of the model's cameras (aiCamera), in order
};

/// The animations and cameras of an imported model. Key times that are NaN or infinite are
/// left out of first_key / last_key (load_model refuses them).
[[nodiscard]] ModelCatalog model_catalog(const aiScene& scene);

}  // namespace kinray
