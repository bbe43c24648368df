#pragma once
// The camera of an imported model: the model's own camera (an aiCamera placed, and possibly
// animated, by its node); scenes/automatic_camera.h frames models without one.
#include <optional>
#include <span>
#include <string>

#include "scenes/model_animation.h"

struct aiScene;

namespace kinray {

/// A model's own camera and its name (that of the aiCamera and of its node).
struct NamedCamera {
  std::string name;
  Camera camera;
};

/// The model's first perspective camera that has a node, with a key at each of `key_seconds`
/// (`key_ticks` in the animation's ticks) when its node moves, else one key at key_seconds[0].
/// aiCamera::mHorizontalFOV is read as the full horizontal angle (as assimp's FBX, COLLADA and
/// glTF importers store it) and turned into the vertical one with mAspect (1 when unset).
/// Returns nothing when the model has no usable camera (orthographic cameras are skipped with a
/// warning). Throws InputError (at `where`) for a camera whose position or directions are NaN.
[[nodiscard]] std::optional<NamedCamera> model_camera(const aiScene& scene, const NodeGraph& graph,
                                                      std::span<const double> key_seconds,
                                                      std::span<const double> key_ticks,
                                                      const std::string& where);

/// True when some vertex of `scene` lies in the view of `camera` (in front of it and inside its
/// field of view on a square image) at one of the camera's key times. assimp 5.2 places some
/// formats' cameras inconsistently (3DS adds the camera position twice, LWS and ASE cameras look
/// along +z), so a model camera that sees nothing of the model is replaced by automatic framing.
[[nodiscard]] bool camera_sees(const Camera& camera, const Scene& scene);

/// Vertical field of view of a model camera whose own is unusable, in degrees.
inline constexpr double kFramingFovDegrees = 45;

}  // namespace kinray
