#pragma once
// Automatic framing: the camera a scene gets when it has none of its own (a model without a
// usable camera) or when `--camera auto` asks for it. It frames what the frames show, not the
// bounds of the whole animation: a figure that walks across a large floor of its own making (a BVH
// walk) is followed by a camera that translates with it, at the distance that keeps its largest
// extent in view; a subject that stays where it is gets a still camera, as before.
//
// The kinetic grid needs no still camera: camera space (docs/design.md) transforms every key into
// the camera's frame at that key and interpolates there, so a camera keyed at the scene's own key
// times keeps every camera-space flightplan piecewise linear with the same keys. The following
// camera only translates (its orientation is fixed), so between two keys a vertex's camera-space
// position is the difference of two linear motions: it stays inside the view, which is convex,
// whenever it is inside at both keys, and that is what the distance below guarantees.
#include <string>
#include <vector>

#include "scenes/scene.h"

namespace kinray {

/// How the automatic camera is placed; the defaults are what `render` uses.
struct FramingConfig {
  double fov_y_degrees = 45;      ///< vertical field of view
  double elevation_degrees = 20;  ///< the camera looks down at the subject from this angle, from +z
  double margin = 1.05;           ///< the framed sphere's radius is enlarged by this factor
  double smoothing_seconds =
      1.0;  ///< the followed path is the subject's centre averaged over this window
  double follow_gain = 1.5;  ///< follow only when the subject then looks this much larger
  /// Frame only what is shown in [begin, end] (`--time A:B`); by default the whole shot.
  double begin = -kInfinity, end = kInfinity;
};

/// The subject at one key time: bounds of the objects visible around it (on the key intervals on
/// either side).
struct FramedKey {
  double time = 0;
  Eigen::AlignedBox3d bounds;
};

/// The bounds of what is visible around each key of the scene's object key grid (the key times of
/// its moving objects inside the shot, and the shot's ends; the camera's keys do not count),
/// restricted to [begin, end] (and those two times) when that lies in the shot.
[[nodiscard]] std::vector<FramedKey> framed_keys(const Scene& scene, double begin = -kInfinity,
                                                 double end = kInfinity);

/// The camera that frames `scene` automatically: still, framing the bounds of everything shown
/// over the shot when that is nearly as tight as following (`follow_gain`); otherwise keyed at
/// every key of framed_keys(), looking at the subject's smoothed centre from a fixed direction and
/// distance. Either way every vertex visible at a key lies in the view at that key (on images at
/// least as wide as tall).
[[nodiscard]] Camera automatic_camera(const Scene& scene, const FramingConfig& config = {});

/// Replaces the scene's camera by automatic_camera() and records why in camera_source.
void frame_automatically(Scene& scene, const std::string& reason, const FramingConfig& config = {});

}  // namespace kinray
