#pragma once
// The camera a render asks for on top of the scene's own: automatic framing, the scene's (a
// model's) own camera, or an explicit still camera, with an optional field of view. The command
// line's --camera, --eye, --target and --fov parse into it (tools/cli/camera_flags.h).
#include <optional>
#include <utility>

#include "scenes/model_import.h"
#include "scenes/scene.h"

namespace kinray {

/// What the camera flags ask for, checked.
struct CameraChoice {
  enum class Mode { scene, automatic, model, view };
  Mode mode = Mode::scene;
  Vec3 eye = Vec3::Zero(), target = Vec3::Zero();  ///< Mode::view
  std::optional<double> fov_y_degrees;             ///< --fov
};

/// Default vertical field of view of an explicit --eye/--target camera, in degrees.
inline constexpr double kExplicitFovDegrees = 45;

/// How a model file is to be loaded for `choice` (its own camera, required or not, or none).
[[nodiscard]] ModelCamera model_camera_choice(const CameraChoice& choice);

/// Gives the loaded `scene` the camera `choice` asks for (models already have theirs from
/// model_camera_choice) and records where it came from in scene.camera_source. An automatic
/// camera frames what is shown in `shot` (--time A:B) when given, else in the whole shot.
void apply_camera_choice(const CameraChoice& choice, Scene& scene,
                         std::optional<std::pair<double, double>> shot = std::nullopt);

}  // namespace kinray
