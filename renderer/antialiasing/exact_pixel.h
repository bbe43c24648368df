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
// With lights (ExactLights) every node is shaded as a lit centre ray is (lighting.h: Lambert
// with a shadow ray per light through the backend's ShadowTracer); a fan triangle whose corners
// or nodes see different light masks is halved towards the shadow boundary and its last pieces
// cut along the boundary's chord, found by bisection on their edges (docs/antialiasing.md,
// "Lights and shadows").
#include <array>
#include <mutex>
#include <span>
#include <vector>

#include "renderer/antialiasing/square_visibility.h"
#include "renderer/frame.h"
#include "renderer/shading.h"
#include "renderer/shadows/lighting.h"
#include "renderer/shadows/shadow_tracer.h"
#include "scenes/camera_space.h"
#include "scenes/camera_space_lights.h"
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
/// The 3-point rule of degree 2 (Strang and Fix 1973): nodes at (2/3, 1/6, 1/6) and its
/// permutations, weights 1/3. Its error is the third derivatives times the size cubed.
[[nodiscard]] std::span<const TriangleQuadratureNode, 3> degree2_triangle_rule();

/// What a lit read-out shades with: the lights at the read-out's time and the tracer of their
/// shadow rays, advanced to that time (its occluded() is called concurrently from the rows).
struct ExactLights {
  const std::vector<CameraSpaceLight>* lights = nullptr;  ///< 1 to kMaxLights
  const ShadowTracer* tracer = nullptr;
};

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
    /// An untextured fan triangle at most this share of the pixel's area takes the degree-2 rule
    /// instead of the degree-5 one. Its error is the shading's third derivatives times the
    /// triangle's size cubed: the shading varies over many pixels, the triangle spans a fraction of
    /// one, so the error is some 1e-7 of the colour, below the 4096-sample reference's noise
    /// (1e-5).
    double low_order_area = 1.0 / 16;
    /// Lit read-out: a fan triangle whose corners or nodes see different light masks (a shadow
    /// boundary crosses it) is halved until its sub-triangles are at most this share of the
    /// pixel's area (a fan triangle is at most half the pixel: at 1/64, three halvings at most).
    /// It bounds the area left unresolved where a sub-triangle holds more than one boundary.
    double shadow_area = 1.0 / 64;
    /// Lit read-out: bisection steps locating a shadow boundary on each of the two edges of a
    /// last sub-triangle it crosses (one corner lit differently from the other two); the
    /// sub-triangle is then cut along the chord between the two crossings, each within 2^-steps
    /// of its edge.
    int shadow_bisections = 8;
  };

  /// Counters for --stats, added up over the pixels read out.
  struct Stats {
    size_t pixels = 0;
    size_t covered_by_one = 0;  ///< pixels inside one triangle nearer than the others
    size_t triangles = 0;       ///< overlapping triangles, visible objects, no repeats
    size_t pieces = 0;          ///< visible convex pieces
    size_t nodes = 0;           ///< quadrature nodes shaded
    size_t shadow_rays = 0;     ///< lit: shadow rays traced (nodes, corners, bisections)
    size_t shadow_cuts = 0;     ///< lit: last sub-triangles cut along a shadow boundary's chord
    Stats& operator+=(const Stats& o) {
      shadow_rays += o.shadow_rays;
      shadow_cuts += o.shadow_cuts;
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
  /// A lit read-out when `lights` is given (its lights not empty): nodes shaded with shadows.
  ExactPixels(const CameraSpaceScene& scene, const PixelRays& image, double t, Config config,
              const ExactLights* lights);

  /// The box-filtered colour of pixel (i, j) (headlight, or lit and shadowed): the mean over its
  /// square, kBackgroundColor where no triangle is seen. `overlapping` must hold every triangle
  /// whose image region meets the square (more do no harm, repeats are ignored); objects invisible
  /// at t are skipped.
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

  /// A point of a lit piece, shaded: its colour as a centre ray's on the same triangle, which
  /// lights face it and which of those reach it, and the functions whose zero lines are kinks or
  /// jumps of the lit shading: [0] the interpolated normal against the view (the normal turns to
  /// face the eye there), [1 + l] the turned normal against light l (its terminator).
  static constexpr size_t kMaxLitKinks = kMaxLights + 1;
  struct LitPoint {
    Vec2 p = Vec2::Zero();
    Color colour = Color::Zero();
    /// Bit l: light l is on the visible side and its cosine is positive, so that its shadow ray
    /// matters (elsewhere max(0, cos) is 0 whatever the ray meets, and none is traced).
    uint32_t faced = 0;
    uint32_t mask = 0;  ///< bit l: faced, and the shadow ray is not blocked
    /// Entries 0..lights written by shade_lit; not zeroed, as the points are made by the
    /// thousand per pixel on the stack (zeroing them was 7% of a lit read-out).
    std::array<double, kMaxLitKinks> kinks;
  };
  /// Shades `points` on the piece's triangle (m_lit_*), all their shadow rays in one batch;
  /// only the lights of `traced` get rays (a bisection needs its boundary's lights' masks only).
  void shade_lit(std::span<const Vec2> points, std::span<LitPoint> out, uint32_t traced = ~0u);
  /// The integral over one convex piece of triangle m_lit_triangle's lit shading.
  Eigen::Vector3d integrate_lit(std::span<const Vec2> piece);
  /// integrate_lit over the triangle of `corners` (shaded), halved `depth` times so far.
  void integrate_lit_triangle(const std::array<LitPoint, 3>& corners, int depth,
                              Eigen::Vector3d& sum);
  /// The rule's nodes on the triangle (a, b, c), shaded into `nodes`; its area (0: a degenerate
  /// triangle, nothing shaded).
  double shade_lit_rule(const Vec2& a, const Vec2& b, const Vec2& c,
                        std::array<LitPoint, 7>& nodes);
  /// The rule over the triangle (a, b, c) with fresh nodes.
  void integrate_lit_rule(const Vec2& a, const Vec2& b, const Vec2& c, Eigen::Vector3d& sum);

  const CameraSpaceScene& m_scene;
  const ExactLights* m_lights = nullptr;
  double m_pixel_area = 0;  ///< the square's, for Config::shadow_area and low_order_area
  // The lit piece being integrated, and the buffers of its shading.
  const TriangleAtInstant* m_lit_triangle = nullptr;
  TriangleRef m_lit_ref;
  std::vector<LitHit> m_lit_hits;
  std::vector<ShadowRay> m_lit_rays;
  std::vector<uint8_t> m_lit_blocked;
  PixelRays m_image;
  double m_t;
  Config m_config;
  SquareVisibility m_visibility;
  std::vector<TriangleRef> m_refs;
  std::vector<TriangleAtInstant> m_at_instant;
  std::vector<ImageTriangle> m_image_triangles;
  std::vector<Vec2> m_kink_side;  ///< one side of a kink's chord in a fan triangle
  std::vector<std::vector<Vec2>> m_cut_pieces, m_cut_next;  ///< a lit triangle cut by its chords
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
/// With `lights`, the read-out is lit (ExactLights; their tracer advanced to frame.time).
template <class Overlapping, class ToRef = SameTriangleRef>
void exact_frame_colours(const CameraSpaceScene& scene, Frame& frame, Overlapping&& overlapping,
                         int threads = 0, ToRef to_ref = {}, ExactPixels::Stats* stats = nullptr,
                         const ExactLights* lights = nullptr) {
  const PixelRays image{frame.width, frame.height};
  std::mutex mutex;
  parallel_for(size_t(frame.height), threads, [&](size_t row) {
    const int j = int(row);
    ExactPixels pixels(scene, image, frame.time, ExactPixels::Config{}, lights);
    for (int i = 0; i < frame.width; ++i)
      frame.color[frame.index(i, j)] = pixels.colour(i, j, overlapping(i, j), to_ref);
    if (stats) {
      const std::lock_guard lock(mutex);
      *stats += pixels.stats();
    }
  });
}

}  // namespace kinray
