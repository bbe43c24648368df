#pragma once
// Where a scene's camera comes from: the scene's own (a built-in, a scene file, BART), a model's
// own camera, automatic framing, or the command line. `kinray info` says which, and
// `--camera model` needs to know whether a model had a camera at all.
#include <string>

namespace kinray {

struct CameraSource {
  enum class Kind { scene, model, automatic, command_line };
  Kind kind = Kind::scene;
  std::string name;    ///< Kind::model: the camera's (and its node's) name
  std::string reason;  ///< Kind::automatic: why, e.g. "the model has no camera"
};

/// "scene", "model", "automatic" or "command line".
[[nodiscard]] inline const char* kind_name(CameraSource::Kind kind) {
  switch (kind) {
    case CameraSource::Kind::model:
      return "model";
    case CameraSource::Kind::automatic:
      return "automatic";
    case CameraSource::Kind::command_line:
      return "command line";
    case CameraSource::Kind::scene:
      break;
  }
  return "scene";
}

}  // namespace kinray
