#pragma once
// Comparing two frames of the same scene at the same time t (docs/design.md, "The references").
// Every pixel whose (object, prim) differ is classified from the exact geometry, recomputed in
// double from the camera-space positions at t (the backends' float depths are not trusted):
//
//  - a *tie* when both sides hit something and the disagreement is within the precision of the
//    backends: both triangles are hit at the same depth within a few float ulps, or the ray
//    passes within epsilon of an edge or vertex of the nearer of the two -- unless the surface is
//    closed across that edge (see below);
//  - a *real* mismatch otherwise: one side sees the background where the other hits a triangle
//    (whatever the depths and edge margins), the farther triangle was reported although a nearer
//    one covers the ray robustly, a backend reported a triangle the ray does not pierce, or the
//    surface is closed across the edge the ray passes near (a crack).
//
// Tolerances are scale-free, sized to the float arithmetic of Embree and GL (see exact_hit.cpp
// and docs/verification.md). The shaded colours are compared separately (PSNR, maximum error).
#include <cstddef>
#include <cstdint>
#include <iosfwd>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "renderer/frame.h"
#include "scenes/camera_space.h"
#include "verification/exact_hit.h"
#include "verification/shadow_diff.h"

namespace kinray {

/// How one pixel of two frames compares.
enum class PixelClass : uint8_t {
  kBackground,  ///< both frames show the background
  kEqual,       ///< same object and prim
  kTie,         ///< different, within the precision of the backends
  kReal,        ///< different beyond it
};

/// Classified differences of one frame.
struct FrameDiff {
  int width = 0, height = 0;
  double time = 0;
  std::vector<PixelClass> pixels;  ///< row-major, row 0 at the top
  size_t mismatch_real = 0, mismatch_tie = 0;
  /// Of the real mismatches, those where a backend leaked through a closed surface at an edge.
  size_t cracks = 0;
  /// Per light, pixels that see the same triangle in both frames but disagree whether the light
  /// reaches it (shadow_diff.h); such a pixel counts once in mismatch_real or mismatch_tie.
  std::vector<LightMismatches> shadow_lights;
  [[nodiscard]] size_t pixel_count() const { return pixels.size(); }
};

/// Shaded-image agreement of two frames: colour error per channel, linear RGB in [0, 1].
struct ColorError {
  double max_error = 0;  ///< largest absolute channel difference
  double mse = 0;        ///< mean squared channel difference
  /// Peak signal-to-noise ratio in dB (peak 1); nullopt when the images are identical.
  [[nodiscard]] std::optional<double> psnr() const;
};

/// Classifies frames of one scene: `tested` against `reference`, which must have the same size
/// and time. Keeps the mesh adjacency it builds for crack detection between calls.
class FrameComparator {
 public:
  /// `scene` must outlive the comparator.
  explicit FrameComparator(const CameraSpaceScene& scene, TieTolerance tolerance = {});
  ~FrameComparator();
  /// Throws std::invalid_argument when the frames differ in size or time.
  [[nodiscard]] FrameDiff compare(const Frame& tested, const Frame& reference);

 private:
  struct Adjacency;
  struct Claim;
  const Adjacency& adjacency(uint32_t object);
  /// False when the claim names no triangle of the scene visible at t.
  bool load_claim(uint32_t object, uint32_t prim, const Vec3& d, double t, Claim& claim) const;
  /// Whether the ray leaks through a crack of the surface that `near` closes (image_diff.cpp).
  bool leaks_through_crack(const Claim& near, const Claim& other, const Vec3& d, double t);
  /// Pixel `px` names different triangles in the frames: a tie or real; `crack` says why.
  PixelClass judge_mismatch(const Frame& tested, const Frame& reference, size_t px, const Vec3& d,
                            bool& crack);
  /// Pixels that see the same triangle but disagree on a light become ties or real mismatches.
  void add_shadow_mismatches(const Frame& tested, const Frame& reference, FrameDiff& diff);

  const CameraSpaceScene& m_scene;
  CameraSpaceLights m_lights;
  TieTolerance m_tolerance;
  std::vector<std::unique_ptr<Adjacency>> m_adjacency;  ///< per object, built on first need
};

/// Colour comparison of two frames of the same size (throws std::invalid_argument otherwise),
/// over every pixel but those `aside` marks (a mask of the frames' size, or nullptr: none).
[[nodiscard]] ColorError compare_colors(const Frame& a, const Frame& b,
                                        const std::vector<uint8_t>* aside = nullptr);

/// Writes the heat map of `diff` as an 8-bit RGB PNG: yellow = tie, red = real mismatch; equal
/// pixels black and background dark grey, or, with a `context` frame of the same size, both as
/// that frame's shaded image in dim grey so the mismatches can be placed. Throws InputError when
/// the file cannot be written.
void write_heat_map(const FrameDiff& diff, const std::string& path, const Frame* context = nullptr);

/// One frame's line of a diff summary.
struct FrameDiffSummary {
  size_t frame = 0;  ///< index in the frame schedule
  double time = 0;
  size_t pixels = 0, mismatch_real = 0, mismatch_tie = 0, cracks = 0;
  std::vector<LightMismatches> shadow_lights;  ///< per light; empty without lights
  std::optional<ColorError> color;             ///< when the colours were compared
  std::string heat_map;                        ///< path of the written heat map, empty if none
};

/// Totals over the frames of a `kinray diff` run.
struct DiffSummary {
  std::string scene, tested, reference;  ///< names, for the table and the JSON
  size_t frames = 0, pixels = 0, mismatch_real = 0, mismatch_tie = 0, cracks = 0;
  std::vector<LightMismatches> shadow_lights;  ///< per light, over all frames
  std::vector<FrameDiffSummary> per_frame;

  /// Appends one frame's line and adds it to the totals.
  void add(FrameDiffSummary line);
  /// Largest real-mismatch count of one frame.
  [[nodiscard]] size_t max_frame_real() const;
  /// The summary as a readable table, one line per frame and a total.
  void print(std::ostream& out) const;
  /// The summary as JSON: {"scene", "tested", "reference", "frames", "pixels", "mismatch_real",
  /// "mismatch_tie", "cracks", "per_frame": [{"frame", "time", "pixels", "mismatch_real",
  /// "mismatch_tie", "cracks", "psnr", "max_error", "heat_map"}]}; psnr is null for identical
  /// colours. With lights, the summary and every frame add "shadows": [{"light",
  /// "mismatch_real", "mismatch_tie"}] (those pixels are already in mismatch_real/tie).
  [[nodiscard]] std::string to_json() const;
  /// Writes to_json() to `path` (write_file_atomically: std::runtime_error when the write fails).
  void write_json(const std::string& path) const;
};

/// A FrameDiffSummary line from a classified frame.
[[nodiscard]] FrameDiffSummary summarize(size_t frame, const FrameDiff& diff);

}  // namespace kinray
