#pragma once
// The camera flags of `render`, `diff`, `bench` and `info`: `--camera auto|model` picks automatic
// framing or the scene's own camera (a model's camera, an error if the model has none);
// `--eye X,Y,Z --target X,Y,Z` place a still camera (up = +y) and `--fov DEG` sets the vertical
// field of view of whichever camera is used. They parse into a CameraChoice
// (renderer/camera_choice.h).
#include <string>

#include "renderer/camera_choice.h"

namespace kinray {

/// The camera flags as given: strings, so that every bad value gets one line naming its flag.
struct CameraParams {
  std::string camera;  ///< --camera auto|model; empty: the scene's own, or automatic for a model
                       ///< without a usable camera
  std::string eye;     ///< --eye X,Y,Z: an explicit still camera at this world point...
  std::string target;  ///< --target X,Y,Z: ... looking at this one
  std::string fov;     ///< --fov DEG: vertical field of view of the camera used
};

/// Checks the flags and says what they ask for. Throws InputError naming the flag: --camera other
/// than auto or model, or with --eye/--target; --eye without --target or the reverse; a point
/// that is not three finite numbers within +-1e15; the eye at the target; --fov not a number in
/// (0.5, 179.5) degrees (what a scene's camera may have).
[[nodiscard]] CameraChoice parse_camera_params(const CameraParams& params);

}  // namespace kinray
