#include "renderer/camera_choice.h"

#include <tuple>

#include "scenes/automatic_camera.h"

namespace kinray {

ModelCamera model_camera_choice(const CameraChoice& choice) {
  switch (choice.mode) {
    case CameraChoice::Mode::model:
      return ModelCamera::own;
    case CameraChoice::Mode::automatic:
    case CameraChoice::Mode::view:
      return ModelCamera::automatic;
    case CameraChoice::Mode::scene:
      break;
  }
  return ModelCamera::own_if_usable;
}

void apply_camera_choice(const CameraChoice& choice, Scene& scene,
                         std::optional<std::pair<double, double>> shot) {
  if (choice.mode == CameraChoice::Mode::view) {
    scene.camera.keys = {Camera::look_at(scene.time_begin, choice.eye, choice.target, Vec3::UnitY(),
                                         choice.fov_y_degrees.value_or(kExplicitFovDegrees))};
    scene.camera_source = {CameraSource::Kind::command_line, "", ""};
    return;
  }
  const bool framed = scene.camera_source.kind == CameraSource::Kind::automatic;
  if (choice.mode == CameraChoice::Mode::automatic || framed) {
    // Automatic framing is placed for its field of view and for what the frames show: a model
    // import framed the whole shot at 45 degrees, so --fov and --time frame it again.
    if (framed && !choice.fov_y_degrees && !shot) return;
    FramingConfig config;
    if (choice.fov_y_degrees) config.fov_y_degrees = *choice.fov_y_degrees;
    if (shot) std::tie(config.begin, config.end) = *shot;
    frame_automatically(scene, framed ? scene.camera_source.reason : "--camera auto", config);
    return;
  }
  if (choice.fov_y_degrees)
    for (CameraKey& key : scene.camera.keys) key.fov_y_degrees = *choice.fov_y_degrees;
}

}  // namespace kinray
