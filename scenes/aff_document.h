#pragma once
// What an AFF scene (BART) says, before it becomes a kinray Scene: the view, lights, materials,
// the tree of static and animated transforms with the shapes under them, the keyframed
// animations by name, and the animation range. aff_parser.h reads it; aff_scene.h turns it into
// flightplans.
#include <array>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "scenes/aff_spline.h"
#include "scenes/scene.h"

namespace kinray {

/// The `v` block: where the camera is and what the image is.
struct AffView {
  Vec3 from = Vec3(0, 0, 1), at = Vec3::Zero(), up = Vec3(0, 1, 0);
  double angle_degrees = 45;  ///< vertical field of view (BART: the y direction when w != h)
  double hither = 1;
  int width = 0, height = 0;
  bool given = false;
};

/// `a start end frames`: the animation BART renders, frames evenly over [start, end] inclusive.
struct AffRange {
  double start = 0, end = 0;
  int frames = 0;
};

/// A triangle mesh in the coordinates of the transform it sits under. Static shapes have one key;
/// animated triangles (`tpa`) carry their own keys, between which they move linearly.
struct AffShape {
  std::string where;  ///< "file:line" of the element, for names and errors
  std::vector<Triangle> triangles;
  std::vector<double> key_times = {0.0};
  std::vector<std::vector<Vec3>> key_positions = {{}};  ///< [key][vertex]
  std::vector<Vec2f> uvs;                               ///< per vertex, or empty
  uint32_t material = 0;                                ///< index into AffDocument::materials
};

/// A node of the transform tree: the root, an `xs` (static T*R*S) or an `x NAME` (animated by the
/// keyframes `k NAME`).
struct AffNode {
  Eigen::Affine3d transform = Eigen::Affine3d::Identity();  ///< static part
  std::string animation;  ///< the `x` name; empty for the root and for `xs`
  std::string where;      ///< "file:line" of the `x` / `xs`
  std::vector<AffShape> shapes;
  std::vector<std::unique_ptr<AffNode>> children;
};

/// `k NAME { transl N ... rot N ... scale N ... }`: the motion of one animated transform (or of
/// the camera, when NAME is "camera"). Missing parts are the identity.
struct AffAnimation {
  std::string where;
  std::optional<PositionSpline> translation, scale;
  std::optional<RotationSpline> rotation;
  std::vector<double> key_times;  ///< every key time of its parts, for the key grid
  /// T(t) * R(t) * S(t), as BART's GetMatrix.
  [[nodiscard]] Eigen::Affine3d matrix(double t) const;
};

struct AffDocument {
  AffView view;
  Color background = Color(0, 0, 0);
  Color ambient = Color(1, 1, 1);
  std::vector<Light> lights;
  std::vector<Material> materials;  ///< one per (fm, texture) pair met, Material::texture set
  std::vector<Texture> textures;
  std::optional<AffRange> range;
  AffNode root;
  std::map<std::string, AffAnimation> animations;
  std::vector<std::string> warnings;  ///< printed by the loader (missing textures)
};

}  // namespace kinray
