#pragma once
// The scene model: triangle meshes whose vertices move along piecewise-linear flightplans,
// objects that appear and disappear, a pinhole camera that may be animated, and materials.
// Everything here is in world space; camera_space.h turns it into what the backends consume.
#include <array>
#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "scenes/camera_source.h"

namespace kinray {

using Vec3 = Eigen::Vector3d;
using Vec2f = Eigen::Vector2f;
using Color = Eigen::Vector3f;  // linear RGB in [0, 1]
using Triangle = std::array<uint32_t, 3>;

inline constexpr double kInfinity = std::numeric_limits<double>::infinity();
/// The largest world coordinate a scene may have. The references trace in float: Embree's edge
/// tests multiply two coordinates and sum such products, which must stay far below float's
/// 3.4e38 (and a model whose buffer is garbage, bounds 1.7e40, is refused as bad input rather
/// than rendered blank). At 1e15 a product is at most 1e30.
inline constexpr double kMaxCoordinate = 1e15;

/// The range of key and shot times, in seconds: |t| at most kMaxTime, and two keys of one
/// flightplan at least kMinKeySpacing apart. The kinetic core solves certificates in time
/// relative to an interval's origin; keys 1e-300 s apart (a mesh sequence at --keyrate 1e300)
/// underflow its arithmetic, and a scene keyed faster than a billion times a second is a typo.
inline constexpr double kMaxTime = 1e9;
inline constexpr double kMinKeySpacing = 1e-9;
/// The largest --keyrate (keys per second) of a model or mesh sequence.
inline constexpr double kMaxKeyrate = 1e6;

/// An RGB texture read from an image file, sampled bilinearly with wrap-around.
struct Texture {
  std::string path;
  int width = 0, height = 0;
  std::vector<Color> texels;  // row-major, row 0 at the top (v = 1)
  [[nodiscard]] Color sample(Vec2f uv) const;
  /// The bilinear blend of texels (i, j) to (i + 1, j + 1), their indices wrapped around, at
  /// fractions ax along i and ay along j: sample() inside one cell.
  [[nodiscard]] Color blend(long long i, long long j, float ax, float ay) const;
  /// The mean of sample() along the straight segment from `from` to `to` in uv, exactly up to
  /// rounding (texture_path.cpp); sample(from) when they are equal. Motion blur averages a
  /// texture sliding under a pixel with it, as antialiasing filters one over a region.
  [[nodiscard]] Color path_average(Vec2f from, Vec2f to) const;
};

struct Material {
  std::string name;
  Color base_color = Color(0.8f, 0.8f, 0.8f);
  int texture = -1;  ///< index into Scene::textures, or -1
};

/// The key positions of an object that moves rigidly, as BART's transform hierarchies move theirs:
/// its vertices once, and one transform per key, shared by every object under the same animated
/// transform. Vertex v stands at key k at transform(k, positions[v]). A BART robot (137,000
/// vertices at 800 keys) takes 3 MB so, against 2.6 GB as explicit key positions.
struct RigidKeys {
  std::vector<Vec3> positions;
  std::shared_ptr<const std::vector<Eigen::Affine3d>> transforms;  ///< [key]
  /// m * p: the one expression every rigid key position is computed with, so that a position
  /// is the same bits wherever it is asked for.
  [[nodiscard]] static Vec3 transform(const Eigen::Affine3d& m, const Vec3& p);
};

/// A triangle mesh whose vertices follow piecewise-linear flightplans that share key times:
/// on [key_times[k], key_times[k+1]] vertex v moves linearly from key_position(k, v) to
/// key_position(k + 1, v). Before the first key and after the last it stands still. One key
/// means a static object. The key positions are explicit (key_positions), or a rigid motion per
/// key (rigid, and key_positions empty).
struct Object {
  std::string name;
  std::vector<Triangle> triangles;
  std::vector<double> key_times;              ///< strictly increasing, at least one
  std::vector<std::vector<Vec3>> key_positions;  ///< [key][vertex], world space; empty if rigid
  std::optional<RigidKeys> rigid;                ///< set instead of key_positions
  std::vector<Vec2f> uvs;                     ///< per vertex, or empty
  uint32_t material = 0;
  double appear = -kInfinity;    ///< visible on [appear, disappear)
  double disappear = kInfinity;

  [[nodiscard]] size_t vertex_count() const {
    if (rigid) return rigid->positions.size();
    return key_positions.empty() ? 0 : key_positions[0].size();
  }
  [[nodiscard]] size_t key_count() const { return key_times.size(); }
  /// How many key position sets the object holds (key_count() once validated).
  [[nodiscard]] size_t key_position_sets() const {
    return rigid ? rigid->transforms->size() : key_positions.size();
  }
  /// World-space position of vertex v at key k.
  [[nodiscard]] Vec3 key_position(size_t k, uint32_t v) const {
    return rigid ? RigidKeys::transform((*rigid->transforms)[k], rigid->positions[v])
                 : key_positions[k][v];
  }
  /// Every vertex's position at key k.
  [[nodiscard]] std::vector<Vec3> key_vertices(size_t k) const;
  /// Turns rigid keys into explicit key positions (for code that edits them).
  void make_keys_explicit();
  /// True when no vertex ever moves in world space.
  [[nodiscard]] bool is_static() const;
  /// Replaces the flightplans (a flightplan update); validates like Scene::validate.
  void set_flightplans(std::vector<double> times, std::vector<std::vector<Vec3>> positions);
  /// World-space position of vertex v at time t.
  [[nodiscard]] Vec3 position(uint32_t v, double t) const;
};

/// One camera key. Camera frame: x right, y up, looking down +z (camera space, docs/design.md).
struct CameraKey {
  double time = 0;
  Vec3 position = Vec3::Zero();
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();  ///< camera-to-world rotation
  double fov_y_degrees = 45;
};

/// A pinhole camera, animated when it has more than one key (position and fov lerp, orientation slerp).
struct Camera {
  std::vector<CameraKey> keys = {CameraKey{}};
  [[nodiscard]] CameraKey at(double t) const;
  /// A key looking from `eye` at `target`, with `up` as the approximate up direction.
  static CameraKey look_at(double time, const Vec3& eye, const Vec3& target, const Vec3& up,
                           double fov_y_degrees);
};

/// A light in world space. Point lights shine from `position` in every direction; directional
/// lights shine along `direction` (from the light towards the scene), as from infinitely far.
struct Light {
  enum class Kind { point, directional };
  Kind kind = Kind::point;
  Vec3 position = Vec3::Zero();            ///< point lights
  Vec3 direction = Vec3(0, 0, -1);         ///< directional lights, unit length
  Color color = Color(1.0f, 1.0f, 1.0f);   ///< linear RGB intensity
};

/// What is wrong with `light`, or nothing: a point light's position must be finite and within
/// +-kMaxCoordinate, a direction finite and not zero, a colour finite (as float) and >= 0.
[[nodiscard]] std::optional<std::string> light_problem(const Light& light);

struct Scene {
  std::string name;
  std::vector<Object> objects;
  std::vector<Material> materials = {Material{}};
  std::vector<Texture> textures;
  Camera camera;
  CameraSource camera_source;  ///< where `camera` comes from (info, --camera model)
  /// Lights of the scene; empty means the renderer's headlight (a light at the eye, no shadows).
  std::vector<Light> lights;
  double time_begin = 0;  ///< the shot, in seconds
  double time_end = 1;
  /// The image size and frame count the scene's author chose (BART's `resolution` and `a`), which
  /// `render` uses unless --size or --frames/--fps/--inbetweens say otherwise; 0: none.
  int image_width = 0, image_height = 0;
  int frame_count = 0;

  /// Throws InputError (with `source` as the place) on NaN/infinite positions, indices out of
  /// range, unsorted or duplicate key times, mismatched key counts, bad materials or an empty shot.
  void validate(const std::string& source) const;
  /// Sorted union of every object's and the camera's key times inside [time_begin, time_end],
  /// plus time_begin and time_end: the keyframe grid that --inbetweens subdivides.
  [[nodiscard]] std::vector<double> key_times() const;
  [[nodiscard]] size_t triangle_count() const;
  [[nodiscard]] size_t vertex_count() const;
  /// World-space bounds of every vertex over every key.
  [[nodiscard]] Eigen::AlignedBox3d bounds() const;
};

}  // namespace kinray
