#pragma once
// The exact box-filtered read-out of a pixel (docs/design.md, "Exact antialiasing"): the mean of
// the shaded radiance over the pixel's square, from the triangles that overlap it (the kinetic
// square structure keeps them; a test finds them by brute force). SquareVisibility cuts the
// square into convex pieces, each seen on one triangle; each piece's shading is integrated by a
// symmetric triangle quadrature whose nodes are shaded exactly as a centre ray is (the same
// functions of shading.h on the node's ray (x, y, 1)), so that the sampling peer and this
// read-out differ by the peer's noise only. No shading is constant over a piece (the headlight's
// view direction turns across the pixel), so every piece takes the rule; pieces are cut finer
// where the shading is not smooth: bilinear texels, and the headlight's |cos| kink.
// Lights (shadow rays at the nodes, their terminators as kinks) are another step: the read-out
// shades by the headlight only.
#include <array>
#include <mutex>
#include <span>
#include <vector>

#include "renderer/antialiasing/square_visibility.h"
#include "renderer/frame.h"
#include "renderer/shading.h"
#include "scenes/camera_space.h"
#include "util/parallel.h"

namespace kinray {

/// A node of a rule on a triangle: barycentric coordinates and a weight (weights sum to 1).
struct TriangleQuadratureNode {
  double l0 = 0, l1 = 0, l2 = 0, weight = 0;
};

/// The 7-point rule of degree 5 (Radon 1948; Strang and Fix 1973, Dunavant 1985): symmetric,
/// positive weights, nodes inside the triangle. The shading over a piece no wider than a pixel is
/// smooth (rational barycentrics, a normalised normal): its error is the sixth derivatives times
/// the pixel's size to the sixth, far below a float colour's rounding.
[[nodiscard]] std::span<const TriangleQuadratureNode, 7> degree5_triangle_rule();

/// Reads pixels out exactly at one time. Holds the buffers of the read-out: keep one per row (or
/// thread), and a pixel allocates nothing once they have grown.
class ExactPixels {
 public:
  struct Config {
    /// Bilinear texels slide under the pixel and have kinks the degree-5 rule does not see: a
    /// textured piece's fan triangles are cut into m x m sub-triangles, each with the rule, m at
    /// least this and enough for a sub-triangle to span half a texel (at most 64).
    int textured_subdivision = 4;
    /// Halvings of a fan triangle that a kink of the shading crosses (the headlight's |cos|
    /// where the interpolated normal turns from the eye), before the last ones are cut along the
    /// kink's chord: the error falls about 20-fold per halving (flythrough at 32 x 24, worst
    /// pixel against 9 halvings: 4e-4 at 0, 5e-7 at 2, the cost 79 -> 165 nodes per pixel).
    int kink_depth = 2;
  };

  /// Counters for --stats, added up over the pixels read out.
  struct Stats {
    size_t pixels = 0;
    size_t covered_by_one = 0;  ///< pixels inside one triangle nearer than the others
    size_t triangles = 0;       ///< overlapping triangles, visible objects, no repeats
    size_t pieces = 0;          ///< visible convex pieces
    size_t nodes = 0;           ///< quadrature nodes shaded
    Stats& operator+=(const Stats& o) {
      pixels += o.pixels;
      covered_by_one += o.covered_by_one;
      triangles += o.triangles;
      pieces += o.pieces;
      nodes += o.nodes;
      return *this;
    }
  };

  ExactPixels(const CameraSpaceScene& scene, const PixelRays& image, double t);
  ExactPixels(const CameraSpaceScene& scene, const PixelRays& image, double t, Config config);

  /// The box-filtered headlight colour of pixel (i, j): the mean over its square,
  /// kBackgroundColor where no triangle is seen. `overlapping` must hold every triangle whose
  /// image region meets the square (more do no harm, repeats are ignored); objects invisible at
  /// t are skipped.
  [[nodiscard]] Color colour(int i, int j, std::span<const TriangleRef> overlapping);
  /// colour() of a set held as another type, to_ref(element) its TriangleRef (the kinetic square
  /// sets' {mesh, triangle}: the kinetic grid's meshes are the objects, in order).
  template <class T, class ToRef>
  [[nodiscard]] Color colour(int i, int j, std::span<const T> overlapping, ToRef&& to_ref) {
    m_refs.clear();
    for (const T& element : overlapping) m_refs.push_back(to_ref(element));
    return colour_of_refs(i, j);
  }

  /// Reads the next pixels out at time t (under the shutter each pixel has its own nodes).
  void set_time(double t) { m_t = t; }

  /// The last colour()'s visible pieces; their owners index triangles().
  [[nodiscard]] const SquareVisibility& visibility() const { return m_visibility; }
  /// The last colour()'s triangles: the visible ones of `overlapping`, sorted, without repeats.
  [[nodiscard]] std::span<const TriangleRef> triangles() const { return m_refs; }
  [[nodiscard]] const Stats& stats() const { return m_stats; }

 private:
  /// colour() of the triangles in m_refs (any order, repeats and invisible objects allowed).
  [[nodiscard]] Color colour_of_refs(int i, int j);
  /// The integral over one convex piece of shade(d) for d = (x, y, 1), by fan triangles, cut
  /// finer when the piece shows `textured` (nullptr: untextured) and along the kinks of shade:
  /// the lines where kink(d) changes sign (the headlight's |cos| at cos = 0; a lit shade would
  /// add its lights' terminators).
  template <class Shade, class Kink>
  Eigen::Vector3d integrate(std::span<const Vec2> piece, const TriangleAtInstant* textured,
                            Shade&& shade, Kink&& kink);

  const CameraSpaceScene& m_scene;
  PixelRays m_image;
  double m_t;
  Config m_config;
  SquareVisibility m_visibility;
  std::vector<TriangleRef> m_refs;
  std::vector<TriangleAtInstant> m_at_instant;
  std::vector<ImageTriangle> m_image_triangles;
  std::vector<Vec2> m_kink_side;  ///< one side of a kink's chord in a fan triangle
  Stats m_stats;
};

/// The exact colour of one pixel (buffers made for the call: for tests and single pixels).
[[nodiscard]] Color exact_pixel_colour(const CameraSpaceScene& scene, const PixelRays& image, int i,
                                       int j, double t, std::span<const TriangleRef> overlapping);

/// The TriangleRef of a TriangleRef.
struct SameTriangleRef {
  [[nodiscard]] TriangleRef operator()(const TriangleRef& ref) const { return ref; }
};

/// Fills frame.color with every pixel's exact colour at frame.time; overlapping(i, j) returns the
/// triangles overlapping pixel (i, j) as a std::span<const T> (valid until the next call on the
/// same thread; it is called concurrently for different rows), to_ref(element) the TriangleRef of
/// each. Rows in parallel, `threads` as parallel_for takes them. Object, prim and depth are left
/// as they are. With `stats`, the frame's counters are added to it.
template <class Overlapping, class ToRef = SameTriangleRef>
void exact_frame_colours(const CameraSpaceScene& scene, Frame& frame, Overlapping&& overlapping,
                         int threads = 0, ToRef to_ref = {}, ExactPixels::Stats* stats = nullptr) {
  const PixelRays image{frame.width, frame.height};
  std::mutex mutex;
  parallel_for(size_t(frame.height), threads, [&](size_t row) {
    const int j = int(row);
    ExactPixels pixels(scene, image, frame.time);
    for (int i = 0; i < frame.width; ++i)
      frame.color[frame.index(i, j)] = pixels.colour(i, j, overlapping(i, j), to_ref);
    if (stats) {
      const std::lock_guard lock(mutex);
      *stats += pixels.stats();
    }
  });
}

}  // namespace kinray
