#include "renderer/motion_blur/embree_motion_blur.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "renderer/antialiasing/pixel_samples.h"
#include "renderer/flush_denormals.h"
#include "renderer/motion_blur/window_pieces.h"
#include "renderer/plane_depth.h"
#include "renderer/shading.h"
#include "renderer/shadows/embree_shadow_tracer.h"
#include "renderer/shadows/lighting.h"
#include "util/parallel.h"
#include "util/stopwatch.h"

namespace kinray {
namespace {

using Clock = std::chrono::steady_clock;

/// The time stratum of each of n spatial strata: a shuffle of 0..n-1 (Fisher-Yates, drawn from
/// splitmix64 of `seed`), so that the samples are stratified in (x, y) and in t at once.
void deal_time_strata(uint64_t seed, int n, std::vector<uint32_t>& strata) {
  strata.resize(size_t(n));
  for (int k = 0; k < n; ++k) strata[size_t(k)] = uint32_t(k);
  for (int k = n - 1; k > 0; --k) {
    seed = splitmix64(seed);
    std::swap(strata[size_t(k)], strata[size_t(seed % uint64_t(k + 1))]);
  }
}

/// Writes positions as Embree's float3 into an Embree-owned buffer.
void write_vertices(RTCGeometry geometry, unsigned slot, const std::vector<Vec3>& positions) {
  auto* out = static_cast<float*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, slot,
                                                          RTC_FORMAT_FLOAT3, 3 * sizeof(float),
                                                          positions.size()));
  if (!out) throw std::runtime_error("Embree could not allocate a vertex buffer");
  for (size_t v = 0; v < positions.size(); ++v)
    for (int c = 0; c < 3; ++c) out[3 * v + size_t(c)] = float(positions[v][c]);
}

}  // namespace

EmbreeMotionBlur::EmbreeMotionBlur(const CameraSpaceScene& scene, RTCDevice device, int threads,
                                   int samples, const CameraSpaceLights* lights, int aa_samples)
    : m_scene(scene),
      m_lights(lights != nullptr && !lights->empty() ? lights : nullptr),
      m_device(device),
      m_threads(resolve_threads(threads)),
      m_samples(samples),
      m_aa_samples(aa_samples) {
  if (aa_samples > 1 && sample_grid_side(aa_samples) == 0)
    throw std::invalid_argument("EmbreeMotionBlur: the antialiasing sample count must be a square");
  m_static.assign(scene.objects.size(), nullptr);
  std::vector<Vec3> positions;
  for (size_t o = 0; o < scene.objects.size(); ++o) {
    const CameraSpaceObject& cs = scene.objects[o];
    if (moves(cs) || scene.triangles(o).empty() || cs.vertex_count == 0) continue;
    m_static[o] = new_geometry(o, 1);
    cs.positions_at(cs.key_times.empty() ? 0.0 : cs.key_times.front(), positions);
    write_vertices(m_static[o], 0, positions);
    rtcCommitGeometry(m_static[o]);
  }
}

EmbreeMotionBlur::~EmbreeMotionBlur() {
  release_pieces();
  for (RTCGeometry g : m_static)
    if (g) rtcReleaseGeometry(g);
}

RTCGeometry EmbreeMotionBlur::new_geometry(size_t object, unsigned time_steps) const {
  const std::vector<Triangle>& triangles = m_scene.triangles(object);
  RTCGeometry geometry = rtcNewGeometry(m_device, RTC_GEOMETRY_TYPE_TRIANGLE);
  rtcSetSharedGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, triangles.data(),
                             0, sizeof(Triangle), triangles.size());
  rtcSetGeometryTimeStepCount(geometry, time_steps);
  // Shadow rays skip the triangle they leave from.
  if (m_lights) EmbreeShadowTracer::install_filter(geometry);
  return geometry;
}

void EmbreeMotionBlur::release_pieces() {
  for (RTCScene s : m_pieces) rtcReleaseScene(s);
  for (RTCGeometry g : m_moving) rtcReleaseGeometry(g);
  m_pieces.clear();
  m_moving.clear();
}

void EmbreeMotionBlur::build(const ShutterWindow& window) {
  release_pieces();
  m_breaks = window_breaks(m_scene, window);

  std::vector<Vec3> positions;
  for (size_t k = 0; k + 1 < m_breaks.size(); ++k) {
    const double s0 = m_breaks[k], s1 = m_breaks[k + 1];
    RTCScene piece = rtcNewScene(m_device);
    rtcSetSceneFlags(piece, RTC_SCENE_FLAG_ROBUST);
    for (size_t o = 0; o < m_scene.objects.size(); ++o) {
      const CameraSpaceObject& cs = m_scene.objects[o];
      if (m_scene.triangles(o).empty() || cs.vertex_count == 0 || !cs.visible((s0 + s1) / 2))
        continue;
      if (m_static[o]) {
        rtcAttachGeometryByID(piece, m_static[o], unsigned(o));
        continue;
      }
      RTCGeometry geometry = new_geometry(o, 2);
      cs.positions_at(s0, positions);
      write_vertices(geometry, 0, positions);
      cs.positions_at(s1, positions);
      write_vertices(geometry, 1, positions);
      rtcCommitGeometry(geometry);
      rtcAttachGeometryByID(piece, geometry, unsigned(o));
      m_moving.push_back(geometry);
    }
    rtcCommitScene(piece);
    m_pieces.push_back(piece);
  }
}

void EmbreeMotionBlur::render(const ShutterWindow& window, Frame& frame) {
  const FlushDenormals flush_denormals;
  auto start = Clock::now();
  build(window);
  m_build_s.push_back(seconds_since(start));
  m_piece_counts.push_back(m_pieces.size());
  start = Clock::now();
  const PixelRays image{frame.width, frame.height};
  frame.time = window.time;
  // Fresh times each frame, and different ones for different sample counts, so that a run at N
  // samples is not correlated with the reference.
  const uint64_t seed = (++m_frame << 20) ^ uint64_t(m_samples) ^ (uint64_t(m_aa_samples) << 40);
  // The piece a time falls in, and the ray time inside it.
  auto piece_of = [&](double t) {
    return std::min<size_t>(
        size_t(std::max<ptrdiff_t>(
            std::upper_bound(m_breaks.begin(), m_breaks.end(), t) - m_breaks.begin() - 1, 0)),
        m_pieces.size() - 1);
  };
  auto piece_time = [&](size_t k, double t) {
    const double s0 = m_breaks[k], s1 = m_breaks[k + 1];
    return s1 > s0 ? float(std::clamp((t - s0) / (s1 - s0), 0.0, 1.0)) : 0.0f;
  };
  auto trace = [&](const Vec3& d, double t, RTCIntersectContext& context) {
    const size_t k = piece_of(t);
    RTCRayHit rh{};
    rh.ray.dir_x = float(d.x());
    rh.ray.dir_y = float(d.y());
    rh.ray.dir_z = 1.0f;
    rh.ray.tnear = 0.0f;
    rh.ray.tfar = std::numeric_limits<float>::infinity();
    rh.ray.time = piece_time(k, t);
    rh.ray.mask = ~0u;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(m_pieces[k], &context, &rh);
    return rh.hit;
  };
  // The light mask of a hit at t: its shadow rays through the piece and ray time of t.
  auto mask_of = [&](const LitHit& hit, const std::vector<CameraSpaceLight>& lights,
                     uint32_t object, uint32_t prim, double t) {
    const size_t k = piece_of(t);
    return light_mask(hit, lights, object, prim, [&](const ShadowRay& ray) {
      return embree_occluded(m_pieces[k], ray, piece_time(k, t));
    });
  };
  // Lights that do not move (a camera of one key) are found once; moving ones are written into
  // the row's `scratch` at each sample's time.
  const std::vector<CameraSpaceLight> still_lights =
      m_lights && m_lights->still() ? m_lights->at(0) : std::vector<CameraSpaceLight>{};
  auto shade = [&](const RTCHit& hit, int i, int j, const Vec3& d, double t,
                   std::vector<CameraSpaceLight>& scratch) -> Color {
    if (hit.geomID == RTC_INVALID_GEOMETRY_ID) return kBackgroundColor;
    if (!m_lights && m_aa_samples > 1) {
      // Off the centre: the headlight as shade_hit colours a ray, on this sample's ray.
      const TriangleAtInstant triangle = triangle_at_instant(
          m_scene, hit.geomID, hit.primID, shading_instant(m_scene, hit.geomID, t));
      return headlight_color(triangle, d, view_direction(d, triangle.tan_half_fov));
    }
    if (!m_lights) return shade_hit(m_scene, image, i, j, hit.geomID, hit.primID, t);
    const LitHit lit = lit_hit(m_scene, hit.geomID, hit.primID, d, t);
    if (still_lights.empty()) m_lights->at(t, scratch);
    const std::vector<CameraSpaceLight>& lights = still_lights.empty() ? scratch : still_lights;
    return lit_color(lit, lights, mask_of(lit, lights, hit.geomID, hit.primID, t));
  };
  if (m_lights) frame.lit.assign(frame.pixel_count(), 0u);
  parallel_for_dynamic(size_t(frame.height), m_threads, [&](size_t row) {
    const FlushDenormals row_flush;
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    std::vector<CameraSpaceLight> scratch;
    std::vector<uint32_t> time_strata;
    const int j = int(row);
    for (int i = 0; i < frame.width; ++i) {
      const size_t p = frame.index(i, j);
      const Vec3 d = image.direction(i, j);
      ColorAverage average;
      if (m_aa_samples > 1) {
        const int m = sample_grid_side(m_aa_samples);
        const PixelSquare square = pixel_square(image, i, j);
        deal_time_strata(splitmix64(seed ^ (uint64_t(p) * 0x9E3779B97F4A7C15ull)), m_aa_samples,
                         time_strata);
        for (int s = 0; s < m_aa_samples; ++s) {
          const Vec2 x = pixel_sample(square, p, s, m);
          const Vec3 ds(x.x(), x.y(), 1.0);
          const double t =
              stratified_time(window, uint32_t(p), int(time_strata[size_t(s)]), m_aa_samples, seed);
          average.add(shade(trace(ds, t, context), i, j, ds, t, scratch), 1.0);
        }
      } else {
        for (int s = 0; s < m_samples; ++s) {
          const double t = stratified_time(window, uint32_t(p), s, m_samples, seed);
          average.add(shade(trace(d, t, context), i, j, d, t, scratch), 1.0);
        }
      }
      frame.color[p] = average.result();
      const RTCHit hit = trace(d, window.time, context);
      if (hit.geomID == RTC_INVALID_GEOMETRY_ID) {
        frame.object[p] = frame.prim[p] = kNoHit;
        frame.depth[p] = std::numeric_limits<float>::infinity();
      } else {
        frame.object[p] = hit.geomID;
        frame.prim[p] = hit.primID;
        frame.depth[p] = exact_plane_depth(m_scene, hit.geomID, hit.primID, d, window.time);
        if (m_lights)
          frame.lit[p] = mask_of(lit_hit(m_scene, hit.geomID, hit.primID, d, window.time),
                                 m_lights->at(window.time), hit.geomID, hit.primID, window.time);
      }
    }
  });
  m_trace_s.push_back(seconds_since(start));
}

void EmbreeMotionBlur::write_stats(nlohmann::json& stats) const {
  double build = 0, trace = 0;
  for (double x : m_build_s) build += x;
  for (double x : m_trace_s) trace += x;
  stats["motion_blur"] = {
      {"samples", m_samples},
      {"aa_samples", m_aa_samples},
      {"build_s", build},
      {"trace_s", trace},
      {"per_frame", {{"pieces", m_piece_counts}, {"build_s", m_build_s}, {"trace_s", m_trace_s}}}};
}

}  // namespace kinray
