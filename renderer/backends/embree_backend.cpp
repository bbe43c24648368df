#include "renderer/backends/embree_backend.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <mutex>
#include <nlohmann/json.hpp>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "renderer/antialiasing/embree_supersampling.h"
#include "renderer/flush_denormals.h"
#include "renderer/motion_blur/embree_motion_blur.h"
#include "renderer/plane_depth.h"
#include "renderer/shading.h"
#include "renderer/shadows/embree_shadow_tracer.h"
#include "renderer/shadows/lighting.h"
#include "util/input_error.h"
#include "util/parallel.h"
#include "util/stopwatch.h"

namespace kinray {
namespace {

using Clock = std::chrono::steady_clock;

const char* error_name(RTCError code) {
  switch (code) {
    case RTC_ERROR_NONE:
      return "no error";
    case RTC_ERROR_UNKNOWN:
      return "unknown error";
    case RTC_ERROR_INVALID_ARGUMENT:
      return "invalid argument";
    case RTC_ERROR_INVALID_OPERATION:
      return "invalid operation";
    case RTC_ERROR_OUT_OF_MEMORY:
      return "out of memory";
    case RTC_ERROR_UNSUPPORTED_CPU:
      return "unsupported CPU";
    case RTC_ERROR_CANCELLED:
      return "cancelled";
  }
  return "error";
}

/// Embree's device configuration. threads=N bounds Embree's build threads like the render threads
/// (0 lets it use all cores). KINRAY_EMBREE_CONFIG is appended: "isa=avx2", for example, runs
/// Embree as on a CPU without AVX-512, which the tests must pass on too.
std::string device_config(int threads) {
  std::string config = threads > 0 ? "threads=" + std::to_string(threads) : "";
  if (const char* extra = std::getenv("KINRAY_EMBREE_CONFIG"); extra && *extra)
    config += (config.empty() ? "" : ",") + std::string(extra);
  return config;
}

/// The one Embree device of the process (creating a device starts Embree's task scheduler, so it
/// is made once and shared by every backend). Errors reported through the callback are recorded
/// and turned into exceptions by check().
class Device {
 public:
  static Device& get(int threads) {
    static Device device(threads);
    return device;
  }
  [[nodiscard]] RTCDevice handle() const { return m_device; }
  [[nodiscard]] int threads() const { return m_threads; }
  [[nodiscard]] uint64_t error_count() const { return m_errors.load(); }
  /// Throws std::runtime_error if Embree reported an error since error_count() was `mark`.
  void check(uint64_t mark, const char* during) const {
    if (m_errors.load() == mark) return;
    std::lock_guard lock(m_mutex);
    throw std::runtime_error(std::string("Embree error during ") + during + ": " + m_last_error);
  }

 private:
  explicit Device(int threads) : m_threads(threads) {
    m_device = rtcNewDevice(device_config(threads).c_str());
    if (!m_device)
      throw std::runtime_error(std::string("cannot create an Embree device: ") +
                               error_name(rtcGetDeviceError(nullptr)));
    rtcSetDeviceErrorFunction(m_device, &Device::on_error, this);
  }
  ~Device() { rtcReleaseDevice(m_device); }

  static void on_error(void* user, RTCError code, const char* message) {
    auto* self = static_cast<Device*>(user);
    std::lock_guard lock(self->m_mutex);
    self->m_last_error =
        std::string(error_name(code)) + (message ? std::string(" (") + message + ")" : "");
    self->m_errors.fetch_add(1);
  }

  RTCDevice m_device = nullptr;
  int m_threads = 0;
  std::atomic<uint64_t> m_errors{0};
  mutable std::mutex m_mutex;
  std::string m_last_error;
};

/// Packet traits: the Embree ray-hit type and the pixel tile a packet covers.
template <int N>
struct Packet;
template <>
struct Packet<4> {
  using RayHit = RTCRayHit4;
  static constexpr int kTileWidth = 2, kTileHeight = 2;
  static void intersect(const int* valid, RTCScene scene, RTCIntersectContext* context,
                        RayHit* rayhit) {
    rtcIntersect4(valid, scene, context, rayhit);
  }
};
template <>
struct Packet<8> {
  using RayHit = RTCRayHit8;
  static constexpr int kTileWidth = 4, kTileHeight = 2;
  static void intersect(const int* valid, RTCScene scene, RTCIntersectContext* context,
                        RayHit* rayhit) {
    rtcIntersect8(valid, scene, context, rayhit);
  }
};
template <>
struct Packet<16> {
  using RayHit = RTCRayHit16;
  static constexpr int kTileWidth = 4, kTileHeight = 4;
  static void intersect(const int* valid, RTCScene scene, RTCIntersectContext* context,
                        RayHit* rayhit) {
    rtcIntersect16(valid, scene, context, rayhit);
  }
};

/// One Scene object as an Embree triangle geometry whose geometry id is the object index.
struct Mesh {
  RTCGeometry geometry = nullptr;
  float* vertices = nullptr;        ///< Embree-owned float3 buffer, padded for 16-byte loads
  bool moving = false;              ///< camera-space positions change over time
  bool enabled = true;              ///< refit mode: current rtcEnable/DisableGeometry state
  std::vector<Vec3> interpolated;   ///< moving objects: camera-space positions at the frame time
  std::span<const Vec3> positions;  ///< the double positions Embree was given this frame
};

std::string join_widths(const std::vector<int>& widths) {
  std::string text;
  for (int w : widths) text += (text.empty() ? "" : ", ") + std::to_string(w);
  return text;
}

/// Ray packet widths the device traces natively: 1, then 4, 8, 16 where supported.
std::vector<int> native_packet_widths(RTCDevice device) {
  std::vector<int> widths = {1};
  if (rtcGetDeviceProperty(device, RTC_DEVICE_PROPERTY_NATIVE_RAY4_SUPPORTED)) widths.push_back(4);
  if (rtcGetDeviceProperty(device, RTC_DEVICE_PROPERTY_NATIVE_RAY8_SUPPORTED)) widths.push_back(8);
  if (rtcGetDeviceProperty(device, RTC_DEVICE_PROPERTY_NATIVE_RAY16_SUPPORTED)) widths.push_back(16);
  return widths;
}

class EmbreeBackend final : public Backend {
 public:
  EmbreeBackend(const CameraSpaceScene& scene, const BackendConfig& config)
      : m_scene(scene),
        m_config(config),
        m_threads(resolve_threads(config.threads)),
        m_device(Device::get(config.threads)),
        m_refit(config.embree_build == EmbreeBuild::kRefit) {
    const RTCDevice device = m_device.handle();
    const uint64_t mark = m_device.error_count();
    m_meshes.resize(scene.objects.size());
    // Shadow rays only when the scene has lights: without them nothing changes.
    if (!scene.scene->lights.empty()) {
      m_shadows = std::make_unique<EmbreeShadowTracer>();
      m_lights = CameraSpaceLights(*scene.scene);
    }
    for (size_t o = 0; o < scene.objects.size(); ++o) {
      const CameraSpaceObject& cs = scene.objects[o];
      const std::vector<Triangle>& triangles = scene.triangles(o);
      Mesh& mesh = m_meshes[o];
      mesh.moving = !cs.is_static;
      mesh.positions = cs.key(0);
      if (triangles.empty() || cs.vertex_count == 0) continue;
      mesh.geometry = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
      // Index buffer shared with the scene model (Triangle is three packed uint32).
      rtcSetSharedGeometryBuffer(mesh.geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                 triangles.data(), 0, sizeof(Triangle), triangles.size());
      // Embree allocates new buffers with the tail padding its 16-byte vector loads need.
      mesh.vertices = static_cast<float*>(
          rtcSetNewGeometryBuffer(mesh.geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                  3 * sizeof(float), cs.vertex_count));
      if (!mesh.vertices) {
        release();
        m_device.check(mark, "vertex buffer allocation");
        throw std::runtime_error("Embree could not allocate a vertex buffer");
      }
      convert(cs.key(0), mesh.vertices);
      if (m_refit)
        rtcSetGeometryBuildQuality(mesh.geometry,
                                   mesh.moving ? RTC_BUILD_QUALITY_REFIT : RTC_BUILD_QUALITY_HIGH);
      else
        rtcSetGeometryBuildQuality(mesh.geometry, kRebuildQuality);
      if (m_shadows) EmbreeShadowTracer::install_filter(mesh.geometry);
      rtcCommitGeometry(mesh.geometry);
    }
    if (m_refit) {
      // Scene quality LOW selects Embree's two-level structure, the one that honours per-geometry
      // REFIT; DYNAMIC tells it the scene is committed again and again.
      m_rtc_scene = rtcNewScene(device);
      rtcSetSceneFlags(m_rtc_scene, RTCSceneFlags(RTC_SCENE_FLAG_DYNAMIC | RTC_SCENE_FLAG_ROBUST));
      rtcSetSceneBuildQuality(m_rtc_scene, RTC_BUILD_QUALITY_LOW);
      for (size_t o = 0; o < m_meshes.size(); ++o)
        if (m_meshes[o].geometry)
          rtcAttachGeometryByID(m_rtc_scene, m_meshes[o].geometry, unsigned(o));
    }
    try {
      m_device.check(mark, "scene set-up");
    } catch (...) {
      release();  // the destructor does not run for a constructor that throws
      throw;
    }
  }

  ~EmbreeBackend() override { release(); }
  EmbreeBackend(const EmbreeBackend&) = delete;
  EmbreeBackend& operator=(const EmbreeBackend&) = delete;

  [[nodiscard]] std::string name() const override { return "embree"; }

  void render(double t, Frame& frame) override {
    const FlushDenormals flush_denormals;
    if (frame.width != m_config.width || frame.height != m_config.height ||
        frame.pixel_count() == 0)
      frame.resize(m_config.width, m_config.height);
    frame.time = t;

    auto start = Clock::now();
    update_scene(t);
    m_build_s.push_back(seconds_since(start));
    if (m_shadows) m_shadows->bind(m_rtc_scene, t);

    start = Clock::now();
    const uint64_t mark = m_device.error_count();
    switch (m_config.embree_packet) {
      case 4:
        trace_packets<4>(frame);
        break;
      case 8:
        trace_packets<8>(frame);
        break;
      case 16:
        trace_packets<16>(frame);
        break;
      default:
        trace_single(frame);
        break;
    }
    m_device.check(mark, "tracing");
    m_trace_s.push_back(seconds_since(start));

    start = Clock::now();
    exact_depths(frame);
    m_depth_s.push_back(seconds_since(start));
  }

  [[nodiscard]] ShadowTracer* shadow_tracer() override { return m_shadows.get(); }

  [[nodiscard]] bool has_motion_blur() const override { return true; }

  [[nodiscard]] bool has_supersampling() const override { return true; }

  void render_supersampled(double t, Frame& frame) override {
    render(t, frame);  // the centre rays: ids and depths, and the scene committed at t
    const auto start = Clock::now();
    if (m_config.aa_samples == 1) {
      // One sample is the centre ray, shaded as the frame loop shades it: bit for bit the frame
      // of render() and shade_frame (or shade_frame_lit through this backend's shadow rays).
      if (m_shadows)
        shade_frame_lit(m_scene, m_lights, *m_shadows, frame, m_threads);
      else
        shade_frame(m_scene, frame, m_threads);
    } else {
      const uint64_t mark = m_device.error_count();
      embree_supersample(m_rtc_scene, m_scene, m_shadows ? &m_lights : nullptr, m_config.aa_samples,
                         m_config.embree_packet, m_threads, frame);
      m_device.check(mark, "antialiasing");
    }
    m_aa_s.push_back(seconds_since(start));
  }

  void render_shutter(const ShutterWindow& window, Frame& frame) override {
    if (frame.width != m_config.width || frame.height != m_config.height ||
        frame.pixel_count() == 0)
      frame.resize(m_config.width, m_config.height);
    if (!m_motion_blur)
      m_motion_blur = std::make_unique<EmbreeMotionBlur>(m_scene, m_device.handle(), m_threads,
                                                         m_config.shutter.samples, &m_lights,
                                                         m_config.aa_samples);
    const uint64_t mark = m_device.error_count();
    m_motion_blur->render(window, frame);
    m_device.check(mark, "motion blur");
  }

  void write_stats(nlohmann::json& stats) const override {
    if (m_motion_blur) m_motion_blur->write_stats(stats);
    if (m_shadows) m_shadows->write_stats(stats);
    auto total = [](const std::vector<double>& v) {
      double sum = 0;
      for (double x : v) sum += x;
      return sum;
    };
    const RTCDevice device = m_device.handle();
    std::vector<int> packets = native_packet_widths(device);
    packets.erase(packets.begin());  // 1 is not a packet
    stats["embree"] = {
        {"version", rtcGetDeviceProperty(device, RTC_DEVICE_PROPERTY_VERSION)},
        {"mode", embree_build_name(m_config.embree_build)},
        {"packet", m_config.embree_packet},
        {"native_packets", packets},
        {"robust", true},
        {"threads", m_threads},
        {"device_threads", m_device.threads()},
        {"frames", m_build_s.size()},
        {"build_s", total(m_build_s)},
        {"trace_s", total(m_trace_s)},
        {"depth_s", total(m_depth_s)},
        {"aa_samples", m_config.aa_samples},
        {"aa_s", total(m_aa_s)},
        {"per_frame", {{"build_s", m_build_s}, {"trace_s", m_trace_s}, {"depth_s", m_depth_s}}},
    };
  }

 private:
  // A scene rebuilt every frame is built once and traced once, so Embree's fast (Morton/binned)
  // build of dynamic content is the right trade between build and trace time.
  static constexpr RTCBuildQuality kRebuildQuality = RTC_BUILD_QUALITY_LOW;

  void release() {
    if (m_rtc_scene) rtcReleaseScene(m_rtc_scene);
    m_rtc_scene = nullptr;
    for (Mesh& mesh : m_meshes) {
      if (mesh.geometry) rtcReleaseGeometry(mesh.geometry);
      mesh.geometry = nullptr;
    }
  }

  void convert(std::span<const Vec3> positions, float* out) const {
    const auto convert_range = [&](size_t begin, size_t end) {
      // The same rounding on every thread: the caller's and oneTBB's run in other floating-point
      // environments (util/parallel.h), and a double converts to a denormal float or to 0.
      const FlushDenormals flush;
      for (size_t v = begin; v < end; ++v) {
        out[3 * v + 0] = float(positions[v].x());
        out[3 * v + 1] = float(positions[v].y());
        out[3 * v + 2] = float(positions[v].z());
      }
    };
    if (positions.size() < 65536)
      convert_range(0, positions.size());
    else
      parallel_chunks(positions.size(), m_threads, convert_range);
  }

  void update_scene(double t) {
    const uint64_t mark = m_device.error_count();
    for (size_t o = 0; o < m_meshes.size(); ++o) {
      Mesh& mesh = m_meshes[o];
      if (!mesh.geometry) continue;
      const CameraSpaceObject& cs = m_scene.objects[o];
      const bool visible = cs.visible(t);
      if (visible && mesh.moving) {
        cs.positions_at(t, mesh.interpolated);
        mesh.positions = mesh.interpolated;
        convert(mesh.positions, mesh.vertices);
        rtcUpdateGeometryBuffer(mesh.geometry, RTC_BUFFER_TYPE_VERTEX, 0);
        rtcCommitGeometry(mesh.geometry);
      }
      if (m_refit && visible != mesh.enabled) {
        if (visible)
          rtcEnableGeometry(mesh.geometry);
        else
          rtcDisableGeometry(mesh.geometry);
        mesh.enabled = visible;
      }
    }
    if (!m_refit) {
      if (m_rtc_scene) rtcReleaseScene(m_rtc_scene);
      m_rtc_scene = rtcNewScene(m_device.handle());
      rtcSetSceneFlags(m_rtc_scene, RTC_SCENE_FLAG_ROBUST);
      rtcSetSceneBuildQuality(m_rtc_scene, kRebuildQuality);
      for (size_t o = 0; o < m_meshes.size(); ++o)
        if (m_meshes[o].geometry && m_scene.objects[o].visible(t))
          rtcAttachGeometryByID(m_rtc_scene, m_meshes[o].geometry, unsigned(o));
    }
    rtcCommitScene(m_rtc_scene);
    m_device.check(mark, embree_build_name(m_config.embree_build));
  }

  /// Runs `band(b, context)` for every b in [0, bands) on all render threads, handing out bands
  /// one at a time (the cost of a band depends on what it sees).
  template <class F>
  void for_each_band(int bands, F&& band) {
    parallel_for_dynamic(size_t(std::max(bands, 0)), m_threads, [&](size_t b) {
      const FlushDenormals flush_denormals;
      RTCIntersectContext context;
      rtcInitIntersectContext(&context);
      context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;  // primary rays of neighbouring pixels
      band(int(b), context);
    });
  }

  void trace_single(Frame& frame) {
    const PixelRays image{frame.width, frame.height};
    constexpr int kRowsPerBand = 4;
    const int bands = (frame.height + kRowsPerBand - 1) / kRowsPerBand;
    for_each_band(bands, [&](int b, RTCIntersectContext& context) {
      for (int j = b * kRowsPerBand; j < std::min(frame.height, (b + 1) * kRowsPerBand); ++j) {
        const float y = float(image.y(j));
        for (int i = 0; i < frame.width; ++i) {
          RTCRayHit rayhit;
          rayhit.ray.org_x = rayhit.ray.org_y = rayhit.ray.org_z = 0.0f;
          rayhit.ray.tnear = 0.0f;
          rayhit.ray.dir_x = float(image.x(i));
          rayhit.ray.dir_y = y;
          rayhit.ray.dir_z = 1.0f;
          rayhit.ray.time = 0.0f;
          rayhit.ray.tfar = std::numeric_limits<float>::infinity();
          rayhit.ray.mask = ~0u;
          rayhit.ray.id = 0;
          rayhit.ray.flags = 0;
          rayhit.hit.geomID = RTC_INVALID_GEOMETRY_ID;
          rayhit.hit.primID = RTC_INVALID_GEOMETRY_ID;
          rtcIntersect1(m_rtc_scene, &context, &rayhit);
          store(frame, frame.index(i, j), rayhit.hit.geomID, rayhit.hit.primID, rayhit.ray.tfar);
        }
      }
    });
  }

  template <int N>
  void trace_packets(Frame& frame) {
    using P = Packet<N>;
    const PixelRays image{frame.width, frame.height};
    const int bands = (frame.height + P::kTileHeight - 1) / P::kTileHeight;
    for_each_band(bands, [&](int b, RTCIntersectContext& context) {
      const int j0 = b * P::kTileHeight;
      for (int i0 = 0; i0 < frame.width; i0 += P::kTileWidth) {
        alignas(64) typename P::RayHit rayhit;
        alignas(64) int valid[N];
        for (int k = 0; k < N; ++k) {
          const int i = i0 + k % P::kTileWidth, j = j0 + k / P::kTileWidth;
          valid[k] = i < frame.width && j < frame.height ? -1 : 0;
          rayhit.ray.org_x[k] = rayhit.ray.org_y[k] = rayhit.ray.org_z[k] = 0.0f;
          rayhit.ray.tnear[k] = 0.0f;
          rayhit.ray.dir_x[k] = float(image.x(i));
          rayhit.ray.dir_y[k] = float(image.y(j));
          rayhit.ray.dir_z[k] = 1.0f;
          rayhit.ray.time[k] = 0.0f;
          rayhit.ray.tfar[k] = std::numeric_limits<float>::infinity();
          rayhit.ray.mask[k] = ~0u;
          rayhit.ray.id[k] = unsigned(k);
          rayhit.ray.flags[k] = 0;
          rayhit.hit.geomID[k] = RTC_INVALID_GEOMETRY_ID;
          rayhit.hit.primID[k] = RTC_INVALID_GEOMETRY_ID;
        }
        P::intersect(valid, m_rtc_scene, &context, &rayhit);
        for (int k = 0; k < N; ++k) {
          if (!valid[k]) continue;
          const int i = i0 + k % P::kTileWidth, j = j0 + k / P::kTileWidth;
          store(frame, frame.index(i, j), rayhit.hit.geomID[k], rayhit.hit.primID[k],
                rayhit.ray.tfar[k]);
        }
      }
    });
  }

  static void store(Frame& frame, size_t p, unsigned geom_id, unsigned prim_id, float tfar) {
    if (geom_id == RTC_INVALID_GEOMETRY_ID) {
      frame.object[p] = kNoHit;
      frame.prim[p] = kNoHit;
      frame.depth[p] = std::numeric_limits<float>::infinity();
    } else {
      frame.object[p] = geom_id;  // attached by ID: the geometry id is the object index
      frame.prim[p] = prim_id;
      frame.depth[p] = tfar;
    }
  }

  /// Replaces Embree's float tfar by the depth of the hit triangle's plane along d_ij in double
  /// (kept when that is degenerate, e.g. a plane seen exactly edge-on).
  void exact_depths(Frame& frame) const {
    const PixelRays image{frame.width, frame.height};
    parallel_for(size_t(frame.height), m_threads, [&](size_t row) {
      const int j = int(row);
      for (int i = 0; i < frame.width; ++i) {
        const size_t p = frame.index(i, j);
        if (frame.object[p] == kNoHit) continue;
        const Mesh& mesh = m_meshes[frame.object[p]];
        const Triangle& tri = m_scene.triangles(frame.object[p])[frame.prim[p]];
        const double z = exact_plane_depth(mesh.positions[tri[0]], mesh.positions[tri[1]],
                                     mesh.positions[tri[2]], image.direction(i, j));
        if (std::isfinite(z) && z > 0) frame.depth[p] = float(z);
      }
    });
  }

  const CameraSpaceScene& m_scene;
  BackendConfig m_config;
  int m_threads = 1;
  Device& m_device;
  std::unique_ptr<EmbreeMotionBlur> m_motion_blur;  ///< made by the first render_shutter
  bool m_refit = true;
  RTCScene m_rtc_scene = nullptr;
  std::vector<Mesh> m_meshes;
  std::unique_ptr<EmbreeShadowTracer> m_shadows;  ///< when the scene has lights
  CameraSpaceLights m_lights;                     ///< the scene's, for motion blur's shading
  std::vector<double> m_build_s, m_trace_s, m_depth_s;
  std::vector<double> m_aa_s;  ///< render_supersampled: the samples' tracing and shading
};

}  // namespace

std::unique_ptr<Backend> make_embree_backend(const CameraSpaceScene& scene,
                                             const BackendConfig& config) {
  if (!is_embree_packet_width(config.embree_packet))
    throw OptionError("embree_packet",
                      "must be 1, 4, 8 or 16, got " + std::to_string(config.embree_packet));
  if (config.width <= 0 || config.height <= 0)
    throw OptionError("width", "width and height must be positive");
  if (config.threads < 0) throw OptionError("threads", "must be 0 (all cores) or more");
  const std::vector<int> widths = embree_packet_widths(config.threads);
  if (std::find(widths.begin(), widths.end(), config.embree_packet) == widths.end())
    throw OptionError("embree_packet", "this machine's Embree has no native " +
                                     std::to_string(config.embree_packet) +
                                     "-wide ray packets (its widths: " + join_widths(widths) + ")");
  return std::make_unique<EmbreeBackend>(scene, config);
}

std::vector<int> embree_packet_widths(int threads) {
  return native_packet_widths(Device::get(threads).handle());
}

}  // namespace kinray
