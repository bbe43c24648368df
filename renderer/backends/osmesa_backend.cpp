#include "renderer/backends/osmesa_backend.h"

#include <GL/gl.h>
#include <GL/glext.h>
#include <GL/osmesa.h>

#include <algorithm>
#include <array>
#include <cstring>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include "renderer/backends/id_rasterizer.h"
#include "util/check.h"
#include "util/input_error.h"

namespace kinray {
namespace {

/// OSMesa's llvmpipe rendering into a framebuffer object with an RGBA8 colour renderbuffer and a
/// 32-bit float depth renderbuffer (OSMesa's own depth buffer is 24-bit fixed point, too coarse
/// for the reversed depth of id_rasterizer.h). Needs GL 3.0 framebuffer objects and
/// ARB_clip_control (GL 4.5); llvmpipe has both.
class OsmesaRasterizer : public IdRasterizer {
 public:
  OsmesaRasterizer() {
    const int attributes[] = {OSMESA_FORMAT,
                              OSMESA_RGBA,
                              OSMESA_DEPTH_BITS,
                              0,
                              OSMESA_STENCIL_BITS,
                              0,
                              OSMESA_ACCUM_BITS,
                              0,
                              OSMESA_PROFILE,
                              OSMESA_COMPAT_PROFILE,
                              0};
    m_context.reset(OSMesaCreateContextAttribs(attributes, nullptr));
    if (!m_context) throw OptionError("backend", "osmesa: cannot create an OSMesa context");
    make_current();
    load(m_clip_control, "glClipControl");
    load(m_gen_framebuffers, "glGenFramebuffers");
    load(m_delete_framebuffers, "glDeleteFramebuffers");
    load(m_bind_framebuffer, "glBindFramebuffer");
    load(m_framebuffer_renderbuffer, "glFramebufferRenderbuffer");
    load(m_check_framebuffer_status, "glCheckFramebufferStatus");
    load(m_gen_renderbuffers, "glGenRenderbuffers");
    load(m_delete_renderbuffers, "glDeleteRenderbuffers");
    load(m_bind_renderbuffer, "glBindRenderbuffer");
    load(m_renderbuffer_storage, "glRenderbufferStorage");

    glGetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &m_max_size);
    GLint viewport[2] = {0, 0};
    glGetIntegerv(GL_MAX_VIEWPORT_DIMS, viewport);
    m_max_size = std::min({m_max_size, viewport[0], viewport[1]});

    m_gen_framebuffers(1, &m_framebuffer);
    m_gen_renderbuffers(2, m_renderbuffers);
    m_bind_framebuffer(GL_FRAMEBUFFER, m_framebuffer);

    // Flat IDs: nothing may alter a fragment's colour between the vertex and the buffer.
    m_clip_control(GL_LOWER_LEFT, GL_ZERO_TO_ONE);
    for (GLenum capability : {GL_DITHER, GL_BLEND, GL_LIGHTING, GL_CULL_FACE, GL_ALPHA_TEST,
                              GL_MULTISAMPLE, GL_POLYGON_SMOOTH, GL_FOG, GL_TEXTURE_2D,
                              GL_DEPTH_CLAMP, GL_SCISSOR_TEST, GL_STENCIL_TEST})
      glDisable(capability);
    glShadeModel(GL_FLAT);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_GREATER);
    glDepthRange(0.0, 1.0);
    glDepthMask(GL_TRUE);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glClearColor(0, 0, 0, 0);
    glClearDepth(0.0);
    glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glEnableClientState(GL_VERTEX_ARRAY);
    glEnableClientState(GL_COLOR_ARRAY);
    check_gl("setting up the ID pipeline");
  }

  ~OsmesaRasterizer() override {
    // The context is destroyed after this body (m_context), taking any leftovers with it.
    if (OSMesaMakeCurrent(m_context.get(), m_dummy, GL_UNSIGNED_BYTE, 1, 1)) {
      m_delete_framebuffers(1, &m_framebuffer);
      m_delete_renderbuffers(2, m_renderbuffers);
    }
  }

  OsmesaRasterizer(const OsmesaRasterizer&) = delete;
  OsmesaRasterizer& operator=(const OsmesaRasterizer&) = delete;

  [[nodiscard]] std::string name() const override { return "osmesa"; }
  [[nodiscard]] int max_size() const override { return m_max_size; }

  void rasterize(const RasterBatch& batch, RasterImage& out) override {
    make_current();
    resize(batch.width, batch.height);
    glViewport(0, 0, batch.width, batch.height);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);

    // Every vertex of a triangle carries its ID as 4 bytes (flat shading uses the provoking one).
    m_colors.resize(batch.clip.size());
    for (size_t tri = 0; tri < batch.ids.size(); ++tri) {
      const uint32_t id = batch.ids[tri];
      const std::array<uint8_t, 4> bytes = {uint8_t(id), uint8_t(id >> 8), uint8_t(id >> 16),
                                            uint8_t(id >> 24)};
      for (int k = 0; k < 3; ++k) m_colors[3 * tri + k] = bytes;
    }
    glVertexPointer(4, GL_FLOAT, 0, batch.clip.data());
    glColorPointer(4, GL_UNSIGNED_BYTE, 0, m_colors.data());
    // glDrawArrays counts in GLsizei; draw in chunks of whole triangles.
    constexpr size_t kChunk = size_t(3) << 24;
    for (size_t first = 0; first < batch.clip.size(); first += kChunk)
      glDrawArrays(GL_TRIANGLES, GLint(first),
                   GLsizei(std::min(kChunk, batch.clip.size() - first)));

    const size_t w = size_t(batch.width), h = size_t(batch.height);
    m_bytes.resize(4 * w * h);
    m_depth.resize(w * h);
    glReadPixels(0, 0, batch.width, batch.height, GL_RGBA, GL_UNSIGNED_BYTE, m_bytes.data());
    glReadPixels(0, 0, batch.width, batch.height, GL_DEPTH_COMPONENT, GL_FLOAT, m_depth.data());
    check_gl("rasterizing");

    // GL's row 0 is the bottom of the image.
    out.id.resize(w * h);
    out.depth.resize(w * h);
    for (size_t gl_row = 0; gl_row < h; ++gl_row) {
      const size_t row = h - 1 - gl_row;
      const uint8_t* bytes = m_bytes.data() + 4 * gl_row * w;
      for (size_t i = 0; i < w; ++i) {
        const uint8_t* b = bytes + 4 * i;
        out.id[row * w + i] =
            uint32_t(b[0]) | uint32_t(b[1]) << 8 | uint32_t(b[2]) << 16 | uint32_t(b[3]) << 24;
      }
      std::memcpy(out.depth.data() + row * w, m_depth.data() + gl_row * w, w * sizeof(float));
    }
  }

 private:
  template <class F>
  void load(F& function, const char* name) {
    function = reinterpret_cast<F>(OSMesaGetProcAddress(name));
    if (!function)
      throw OptionError("backend", std::string("osmesa: this OSMesa lacks ") + name +
                                               " (needs framebuffer objects and clip control)");
  }

  void make_current() {
    if (!OSMesaMakeCurrent(m_context.get(), m_dummy, GL_UNSIGNED_BYTE, 1, 1))
      throw std::runtime_error("osmesa: cannot make the context current");
    if (m_bind_framebuffer) m_bind_framebuffer(GL_FRAMEBUFFER, m_framebuffer);
  }

  void resize(int width, int height) {
    if (width == m_width && height == m_height) return;
    KINRAY_CHECK(width > 0 && height > 0 && width <= m_max_size && height <= m_max_size);
    m_bind_renderbuffer(GL_RENDERBUFFER, m_renderbuffers[0]);
    m_renderbuffer_storage(GL_RENDERBUFFER, GL_RGBA8, width, height);
    m_bind_renderbuffer(GL_RENDERBUFFER, m_renderbuffers[1]);
    m_renderbuffer_storage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT32F, width, height);
    m_framebuffer_renderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER,
                               m_renderbuffers[0]);
    m_framebuffer_renderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER,
                               m_renderbuffers[1]);
    if (m_check_framebuffer_status(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
      throw std::runtime_error("osmesa: the RGBA8 + float depth framebuffer is incomplete");
    GLint bits[2] = {0, 0};
    glGetIntegerv(GL_RED_BITS, &bits[0]);
    glGetIntegerv(GL_ALPHA_BITS, &bits[1]);
    if (bits[0] != 8 || bits[1] != 8)
      throw std::runtime_error("osmesa: the colour buffer does not have 8 bits per channel");
    m_width = width;
    m_height = height;
  }

  static void check_gl(const char* doing) {
    const GLenum error = glGetError();
    if (error != GL_NO_ERROR)
      throw std::runtime_error("osmesa: GL error " + std::to_string(error) + " while " + doing);
  }

  std::unique_ptr<std::remove_pointer_t<OSMesaContext>, decltype(&OSMesaDestroyContext)> m_context{
      nullptr, &OSMesaDestroyContext};
  uint32_t m_dummy[1] = {
      0};  ///< OSMesa needs a bound buffer; drawing goes to the framebuffer object
  GLint m_max_size = 0;
  int m_width = 0, m_height = 0;
  GLuint m_framebuffer = 0, m_renderbuffers[2] = {0, 0};
  std::vector<std::array<uint8_t, 4>> m_colors;
  std::vector<uint8_t> m_bytes;
  std::vector<float> m_depth;

  PFNGLCLIPCONTROLPROC m_clip_control = nullptr;
  PFNGLGENFRAMEBUFFERSPROC m_gen_framebuffers = nullptr;
  PFNGLDELETEFRAMEBUFFERSPROC m_delete_framebuffers = nullptr;
  PFNGLBINDFRAMEBUFFERPROC m_bind_framebuffer = nullptr;
  PFNGLFRAMEBUFFERRENDERBUFFERPROC m_framebuffer_renderbuffer = nullptr;
  PFNGLCHECKFRAMEBUFFERSTATUSPROC m_check_framebuffer_status = nullptr;
  PFNGLGENRENDERBUFFERSPROC m_gen_renderbuffers = nullptr;
  PFNGLDELETERENDERBUFFERSPROC m_delete_renderbuffers = nullptr;
  PFNGLBINDRENDERBUFFERPROC m_bind_renderbuffer = nullptr;
  PFNGLRENDERBUFFERSTORAGEPROC m_renderbuffer_storage = nullptr;
};

}  // namespace

std::unique_ptr<IdRasterizer> make_osmesa_rasterizer() {
  return std::make_unique<OsmesaRasterizer>();
}

std::unique_ptr<Backend> make_osmesa_backend(const CameraSpaceScene& scene,
                                             const BackendConfig& config) {
  return std::make_unique<RasterBackend>(scene, config, make_osmesa_rasterizer());
}

}  // namespace kinray
