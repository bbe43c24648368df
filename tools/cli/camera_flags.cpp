#include "tools/cli/camera_flags.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>

#include "tools/cli/vector_flag.h"
#include "util/input_error.h"

namespace kinray {
namespace {

Vec3 parse_point(const std::string& text, const char* flag) {
  const std::optional<Vec3> point = parse_vector3(text);
  if (!point)
    throw InputError(flag, "expected a point X,Y,Z of three finite numbers, got '" + text + "'");
  if (point->cwiseAbs().maxCoeff() > kMaxCoordinate)
    throw InputError(flag,
                     "coordinates must lie within +-1e15 (what the float references can "
                     "trace), got '" +
                         text + "'");
  return *point;
}

double parse_fov(const std::string& text) {
  char* end = nullptr;
  errno = 0;
  const double fov = std::strtod(text.c_str(), &end);
  const bool number = !text.empty() && errno == 0 && end == text.c_str() + text.size();
  if (!number || !(fov > 0.5 && fov < 179.5))
    throw InputError("--fov",
                     "expected the vertical field of view in degrees, more than 0.5 and "
                     "less than 179.5, got '" +
                         text + "'");
  return fov;
}

}  // namespace

CameraChoice parse_camera_params(const CameraParams& params) {
  CameraChoice choice;
  const bool eye = !params.eye.empty(), target = !params.target.empty();
  if (!params.camera.empty()) {
    if (params.camera == "auto")
      choice.mode = CameraChoice::Mode::automatic;
    else if (params.camera == "model")
      choice.mode = CameraChoice::Mode::model;
    else
      throw InputError("--camera", "expected auto or model, got '" + params.camera +
                                       "' (an explicit camera is --eye X,Y,Z --target X,Y,Z)");
    if (eye || target)
      throw InputError("--camera",
                       "cannot be combined with --eye and --target, which place the "
                       "camera themselves");
  }
  if (eye != target)
    throw InputError(eye ? "--eye" : "--target",
                     eye ? "needs --target X,Y,Z too (the point the camera looks at)"
                         : "needs --eye X,Y,Z too (where the camera stands)");
  if (eye) {
    choice.mode = CameraChoice::Mode::view;
    choice.eye = parse_point(params.eye, "--eye");
    choice.target = parse_point(params.target, "--target");
    if (!((choice.target - choice.eye).norm() > 0))
      throw InputError("--target",
                       "is the eye itself (" + params.eye + "): the camera would look nowhere");
  }
  if (!params.fov.empty()) choice.fov_y_degrees = parse_fov(params.fov);
  return choice;
}

}  // namespace kinray
