#pragma once
// The rasterizing reference (docs/design.md, "The references"): the camera-space triangles at frame
// time t are rasterized off-screen into an ID buffer and a depth buffer. This file holds the part
// that does not depend on the rasterizer: the projection that makes GL's pixel centres the
// centre rays d_ij, the exact 32-bit ID encoding, and the decoding back into a Frame. The
// rasterizer itself (OSMesa today; OSMesa is gone from Mesa 25.1) sits behind IdRasterizer, so
// another off-screen GL (EGL surfaceless, a software rasterizer) can replace it without touching
// the rest.
//
// Projection. Camera space has the fov folded in, so a point (x, y, z) lies on the centre ray of
// the continuous pixel position x / z = PixelRays::x, y / z = PixelRays::y. Sending the clip-space
// vertex (x / aspect, y, near, z) (aspect = W / H) makes GL's normalized device coordinates exactly
// the centre-ray coordinates, so GL's pixel centres (i + 1/2, rows counted from the bottom) sample
// the rays d_ij. The depth is "reversed and infinite": with clip control [0, 1] the window depth
// is near / z, 1 at the near plane and 0 at infinity, stored as a 32-bit float, so its relative
// precision is that of a float (~6e-8) at every distance; the depth test keeps the greater value.
// The only clipping in depth is GL's near plane z = near: triangles crossing the eye plane lose
// the sliver nearer than `near` (the sign rule of docs/design.md needs no clipping; this is the one
// expected geometric difference, part of the fill-rule budget of `kinray diff --against osmesa`).
#include <Eigen/Core>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "renderer/backends/backend.h"

namespace kinray {

/// One off-screen pass: triangles in the clip space described above, each with its ID.
struct RasterBatch {
  int width = 0, height = 0;
  std::span<const Eigen::Vector4f> clip;  ///< 3 vertices per triangle: (x / aspect, y, near, z)
  std::span<const uint32_t> ids;          ///< one per triangle, never 0 (0 is the background)
};

/// What a rasterizer returns, in image order (row 0 at the top, i.e. GL's last row).
struct RasterImage {
  std::vector<uint32_t> id;  ///< ID of the nearest fragment whose pixel centre is covered; 0 = none
  std::vector<float> depth;  ///< window depth near / z of that fragment; 0 = none
};

/// An off-screen rasterizer of flat-coloured ID triangles: no lighting, blending, dithering or
/// multisampling, 8 bits per channel (the ID's four bytes are R, G, B, A, least significant
/// first), a float depth buffer compared with "greater", clip-space depth range [0, 1].
class IdRasterizer {
 public:
  virtual ~IdRasterizer() = default;
  [[nodiscard]] virtual std::string name() const = 0;
  /// The largest width and height it renders.
  [[nodiscard]] virtual int max_size() const = 0;
  /// Rasterizes `batch` into `out` (resized to width * height, at most max_size() per side).
  virtual void rasterize(const RasterBatch& batch, RasterImage& out) = 0;
};

/// IDs: triangle `prim` of object `o` gets first_id[o] + prim, with first_id[0] = 1 (0 is the
/// background), so every triangle of the scene has its own 32-bit ID. Throws InputError when the
/// scene has more triangles than 32 bits can name.
class TriangleIds {
 public:
  explicit TriangleIds(const CameraSpaceScene& scene);
  [[nodiscard]] uint32_t id(uint32_t object, uint32_t prim) const { return m_first[object] + prim; }
  /// The (object, prim) of a non-zero id.
  void decode(uint32_t id, uint32_t& object, uint32_t& prim) const;

 private:
  std::vector<uint32_t> m_first;  ///< first id of each object, then one past the last
};

/// A Backend that rasterizes the scene at t with an IdRasterizer and decodes its output into a
/// Frame: object and prim from the ID, depth z = near / window depth. The colour is left to the
/// shared shade_frame, so it is identical to the other backends' wherever the IDs agree.
class RasterBackend : public Backend {
 public:
  /// `scene` must outlive the backend. Throws InputError for an image size the rasterizer cannot
  /// render.
  RasterBackend(const CameraSpaceScene& scene, const BackendConfig& config,
                std::unique_ptr<IdRasterizer> rasterizer);
  [[nodiscard]] std::string name() const override { return m_rasterizer->name(); }
  void render(double t, Frame& frame) override;
  void write_stats(nlohmann::json& stats) const override;

 private:
  const CameraSpaceScene& m_scene;
  BackendConfig m_config;
  std::unique_ptr<IdRasterizer> m_rasterizer;
  TriangleIds m_ids;
  std::vector<std::vector<Vec3>> m_positions;  ///< per object, at the current frame time
  std::vector<Eigen::Vector4f> m_clip;
  std::vector<uint32_t> m_batch_ids;
  RasterImage m_image;
  size_t m_frames = 0, m_triangles_sent = 0;
  double m_seconds = 0;
};

}  // namespace kinray
