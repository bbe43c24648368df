#pragma once
// Shading shared by every backend: the backends only decide which triangle each pixel's centre
// ray hits; the colour is computed here from (object, prim) alone, so frames whose ID buffers
// agree have identical colours.
#include <array>

#include "renderer/frame.h"
#include "scenes/camera_space.h"
#include "scenes/camera_space_lights.h"

namespace kinray {

inline const Color kBackgroundColor(0.06f, 0.07f, 0.09f);
/// The share of the base colour that every hit receives, lit or not.
inline constexpr float kAmbient = 0.15f;
/// The share a light at normal incidence adds (white light: ambient + diffuse = 1).
inline constexpr float kDiffuse = 0.85f;

/// What shading needs of the exact hit of pixel (i, j) on (object, prim) at time t.
struct SurfacePoint {
  Vec3 ray = Vec3::Zero();                                       ///< the pixel's direction d_ij
  Vec3 p0 = Vec3::Zero(), p1 = Vec3::Zero(), p2 = Vec3::Zero();  ///< camera-space vertices at t
  Eigen::Vector3f normal =
      Eigen::Vector3f(0, 0, -1);  ///< interpolated vertex normal, true camera space
  Eigen::Vector3f view = Eigen::Vector3f(0, 0, 1);  ///< unit view direction, true camera space
  double tan_half_fov = 1;                          ///< undoes the fov folding (unfold())
  Color base = Color::Zero();                       ///< base colour times texture
};

/// The texture `object` of `scene` is shaded with: its material's, when the object has texture
/// coordinates; nullptr otherwise.
[[nodiscard]] const Texture* shading_texture(const Scene& scene, const Object& object);

/// What every pixel's shading on one object at one time shares: where the time falls on the
/// object's keys and the camera's field of view. Motion blur shades many pixels at the same
/// quadrature nodes and computes this once per node.
struct ShadingInstant {
  KeySegment segment;       ///< the time on the object's key_times
  double tan_half_fov = 1;  ///< CameraSpaceScene::tan_half_fov at the time
};

/// The ShadingInstant of `object` at time t.
[[nodiscard]] ShadingInstant shading_instant(const CameraSpaceScene& scene, uint32_t object,
                                             double t);

/// What shading needs of one triangle at one instant, whatever the ray: its camera-space
/// vertices, the parts of Moller-Trumbore that do not depend on the ray, its vertex normals and
/// its material. Motion blur shades every pixel of a front at the same quadrature nodes, and
/// builds this once per front and node rather than once per pixel; surface_point of a pixel
/// from it is bit for bit the one built from (object, prim) at that instant.
struct TriangleAtInstant {
  Vec3 p0 = Vec3::Zero(), p1 = Vec3::Zero(), p2 = Vec3::Zero();
  Vec3 e1 = Vec3::Zero(), e2 = Vec3::Zero();  ///< p1 - p0, p2 - p0
  Vec3 qvec = Vec3::Zero();                   ///< (-p0) x e1
  std::array<Eigen::Vector3f, 3> normals;     ///< the vertex normals at the instant
  std::array<uint32_t, 3> vertices{};         ///< the object's vertex ids (for the uvs)
  const Object* source = nullptr;
  Color base = Color::Zero();        ///< the material's base colour
  const Texture* texture = nullptr;  ///< the material's texture, when it has uvs
  double tan_half_fov = 1;
};

/// One triangle over one key segment of its object (the keys k and k + 1): its vertices and
/// vertex normals at key k, their steps to key k + 1, and its material. At any instant of the
/// segment its TriangleAtInstant is then one blend per vertex, the operations of
/// CameraSpaceObject::position and normal on the same values, so bit for bit the same. Motion
/// blur shades a front at four nodes of each interval, and there the key lookups and loads were
/// most of the work of building the triangle at each node.
class TriangleOverSegment {
 public:
  /// An empty triangle (holds() nothing), to be assigned.
  TriangleOverSegment() = default;
  TriangleOverSegment(const CameraSpaceScene& scene, uint32_t object, uint32_t prim, size_t k);
  /// Built for (object, prim) on key segment k.
  [[nodiscard]] bool holds(uint32_t object, uint32_t prim, size_t k) const {
    return m_source != nullptr && m_object == object && m_prim == prim && m_k == k;
  }
  /// The triangle at `instant`, whose segment must be this one's (instant.segment.k == k).
  [[nodiscard]] TriangleAtInstant at(const ShadingInstant& instant) const;

 private:
  std::array<Vec3, 3> m_start, m_step;  ///< positions at key k, key k + 1 minus key k
  std::array<Eigen::Vector3f, 3> m_normal_start, m_normal_step;
  bool m_moving = false;  ///< the object has keys to blend (else m_start is the position)
  std::array<uint32_t, 3> m_vertices{};
  const Object* m_source = nullptr;
  Color m_base = Color::Zero();
  const Texture* m_texture = nullptr;
  uint32_t m_object = 0, m_prim = 0;
  size_t m_k = 0;
};

/// The TriangleAtInstant of (object, prim) at `instant`:
/// TriangleOverSegment(scene, object, prim, instant.segment.k).at(instant).
[[nodiscard]] TriangleAtInstant triangle_at_instant(const CameraSpaceScene& scene, uint32_t object,
                                                    uint32_t prim, const ShadingInstant& instant);

/// The triangles a row's pixels hit at one time, walked left to right: a triangle covers a few
/// consecutive pixels of a row and an object long runs of them, so the object's instant is found
/// once per run of its pixels and the triangle at that instant once per run of its own (the
/// values of shading_instant and triangle_at_instant bit for bit: the same functions on the same
/// values). Found again per pixel, the key search, the fov's tangent and the blend of the
/// triangle's vertices cost a quarter of the shading (wavy-sphere at 40,000 triangles, 512x512,
/// 385 frames: 1.7 -> 1.3 s).
class RowTriangles {
 public:
  RowTriangles(const CameraSpaceScene& scene, double t) : m_scene(scene), m_t(t) {}
  /// (object, prim) at the time.
  const TriangleAtInstant& at(uint32_t object, uint32_t prim) {
    if (object != m_object) {
      m_object = object;
      m_instant = shading_instant(m_scene, object, m_t);
      m_prim = kNoHit;
    }
    if (prim != m_prim) {
      m_prim = prim;
      m_triangle = triangle_at_instant(m_scene, object, prim, m_instant);
    }
    return m_triangle;
  }

 private:
  const CameraSpaceScene& m_scene;
  double m_t;
  uint32_t m_object = kNoHit, m_prim = kNoHit;
  ShadingInstant m_instant;
  TriangleAtInstant m_triangle;
};

/// The unit view direction of the pixel direction d (true camera space): SurfacePoint::view.
[[nodiscard]] Eigen::Vector3f view_direction(const Vec3& d, double tan_half_fov);

/// The SurfacePoint of the ray d on `triangle`, its view direction view_direction(d,
/// triangle.tan_half_fov) given (the same for every node of a pixel under a fixed fov).
[[nodiscard]] SurfacePoint surface_point(const TriangleAtInstant& triangle, const Vec3& d,
                                         const Eigen::Vector3f& view);

/// The texture coordinates of ray d's hit on `triangle`, as surface_point samples its texture
/// (zero when it has none).
[[nodiscard]] Vec2f surface_uv(const TriangleAtInstant& triangle, const Vec3& d);
/// The headlight Lambert colour of a surface point (shade_hit's).
[[nodiscard]] Color headlight_color(const SurfacePoint& surface);

/// headlight_color(surface_point(triangle, d, view)) without the rest of the SurfacePoint.
[[nodiscard]] Color headlight_color(const TriangleAtInstant& triangle, const Vec3& d,
                                    const Eigen::Vector3f& view);

/// The SurfacePoint of pixel (i, j) hitting (object, prim) at `instant`.
[[nodiscard]] SurfacePoint surface_point(const CameraSpaceScene& scene, const PixelRays& image,
                                         int i, int j, uint32_t object, uint32_t prim,
                                         const ShadingInstant& instant);

/// Base colour (or texture) with a two-sided headlight Lambert term, using vertex normals
/// interpolated at the exact hit of pixel (i, j) on (object, prim) at time t.
[[nodiscard]] Color shade_hit(const CameraSpaceScene& scene, const PixelRays& image, int i,
                              int j, uint32_t object, uint32_t prim, double t);

/// shade_hit at `instant` (the same colour as at its time, bit for bit).
[[nodiscard]] Color shade_hit(const CameraSpaceScene& scene, const PixelRays& image, int i,
                              int j, uint32_t object, uint32_t prim, const ShadingInstant& instant);

/// Fills frame.color from frame.object / frame.prim (all cores).
void shade_frame(const CameraSpaceScene& scene, Frame& frame, int threads = 0);

}  // namespace kinray
