#include "verification/image_diff.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdio>
#include <map>
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <ostream>
#include <stdexcept>
#include <unordered_map>

#include "renderer/output/image_io.h"
#include "util/input_error.h"

namespace kinray {

/// Which triangles of an object share each edge. Vertices are welded by position (equal at every
/// key), because imported meshes split vertices along UV and normal seams.
struct FrameComparator::Adjacency {
  std::vector<uint32_t> weld;  ///< vertex -> representative vertex with the same flightplan
  std::unordered_map<uint64_t, std::vector<uint32_t>> edges;  ///< welded edge -> prims

  [[nodiscard]] uint64_t key(uint32_t a, uint32_t b) const {
    a = weld[a];
    b = weld[b];
    if (a > b) std::swap(a, b);
    return uint64_t(a) << 32 | b;
  }
};

FrameComparator::FrameComparator(const CameraSpaceScene& scene, TieTolerance tolerance)
    : m_scene(scene),
      m_lights(*scene.scene),
      m_tolerance(tolerance),
      m_adjacency(scene.objects.size()) {}

FrameComparator::~FrameComparator() = default;

const FrameComparator::Adjacency& FrameComparator::adjacency(uint32_t object) {
  std::unique_ptr<Adjacency>& slot = m_adjacency[object];
  if (slot) return *slot;
  slot = std::make_unique<Adjacency>();
  const CameraSpaceObject& cs = m_scene.objects[object];
  const size_t nv = cs.vertex_count, nk = cs.key_times.size();
  slot->weld.resize(nv);
  std::map<std::array<double, 3>, uint32_t> first;
  for (uint32_t v = 0; v < nv; ++v) {
    const Vec3& p = cs.positions[v];
    const auto [it, inserted] = first.try_emplace({p.x(), p.y(), p.z()}, v);
    uint32_t representative = it->second;
    for (size_t k = 1; k < nk && representative != v; ++k)
      if (cs.positions[k * nv + v] != cs.positions[k * nv + representative]) representative = v;
    slot->weld[v] = representative;
  }
  const std::vector<Triangle>& triangles = m_scene.triangles(object);
  for (uint32_t prim = 0; prim < triangles.size(); ++prim)
    for (int k = 0; k < 3; ++k)
      slot->edges[slot->key(triangles[prim][size_t(k)], triangles[prim][size_t((k + 1) % 3)])]
          .push_back(prim);
  return *slot;
}

/// An object's triangle that a frame names at a pixel, with its exact hit of the pixel's ray.
struct FrameComparator::Claim {
  uint32_t object = kNoHit, prim = kNoHit;
  std::array<Vec3, 3> v;
  ExactHit hit;
};

bool FrameComparator::load_claim(uint32_t object, uint32_t prim, const Vec3& d, double t,
                                 Claim& claim) const {
  claim.object = object;
  claim.prim = prim;
  if (object >= m_scene.objects.size()) return false;
  const CameraSpaceObject& cs = m_scene.objects[object];
  const std::vector<Triangle>& triangles = m_scene.triangles(object);
  if (prim >= triangles.size() || !cs.visible(t)) return false;
  for (size_t k = 0; k < 3; ++k) claim.v[k] = cs.position(triangles[prim][k], t);
  claim.hit = exact_hit(claim.v, d, m_tolerance.edge);
  return claim.hit.valid;
}

// A crack: the ray passes near exactly one edge of `near` (not a vertex), and the object's
// triangle across that edge lies on the other side of it in the image and is pierced too, so
// the union of the two covers the ray robustly; whoever reported the background or something
// behind both leaked through.
bool FrameComparator::leaks_through_crack(const Claim& near, const Claim& other, const Vec3& d,
                                          double t) {
  if (std::popcount(near.hit.near_edges) != 1) return false;
  const int k = std::countr_zero(near.hit.near_edges);
  const Triangle& tri = m_scene.triangles(near.object)[near.prim];
  const uint32_t a = tri[size_t(k)], b = tri[size_t((k + 1) % 3)], c = tri[size_t((k + 2) % 3)];
  const Adjacency& adj = adjacency(near.object);
  const auto it = adj.edges.find(adj.key(a, b));
  if (it == adj.edges.end()) return false;
  const CameraSpaceObject& cs = m_scene.objects[near.object];
  const Vec3& p = near.v[size_t(k)];
  const Vec3& q = near.v[size_t((k + 1) % 3)];
  const Vec3 edge_normal = p.cross(q);
  const double side = edge_normal.dot(near.v[size_t((k + 2) % 3)]);
  for (uint32_t prim : it->second) {
    if (prim == near.prim) continue;
    if (other.object == near.object && other.prim == prim) return false;  // the neighbour: a tie
    const Triangle& across = m_scene.triangles(near.object)[prim];
    uint32_t third = kNoHit;
    for (uint32_t w : across)
      if (adj.weld[w] != adj.weld[a] && adj.weld[w] != adj.weld[b]) third = w;
    if (third == kNoHit || adj.weld[c] == adj.weld[third]) continue;
    if (!(side * edge_normal.dot(cs.position(third, t)) < 0))
      continue;  // folds back: a silhouette
    std::array<Vec3, 3> v;
    for (size_t m = 0; m < 3; ++m) v[m] = cs.position(across[m], t);
    const ExactHit hit = exact_hit(v, d, m_tolerance.edge);
    if (!hit.valid || std::popcount(hit.near_edges) > 1) continue;
    // Something at the depth of either side (a duplicate of the neighbour, say) is no leak.
    if (other.object == kNoHit ||
        (other.hit.z > std::max(near.hit.z, hit.z) && !same_depth(other.hit, hit, m_tolerance) &&
         !same_depth(other.hit, near.hit, m_tolerance)))
      return true;
  }
  return false;
}

PixelClass FrameComparator::judge_mismatch(const Frame& tested, const Frame& reference, size_t px,
                                           const Vec3& d, bool& crack) {
  const bool a_hit = tested.object[px] != kNoHit, b_hit = reference.object[px] != kNoHit;
  const double t = tested.time;
  Claim a, b;
  const bool a_valid = a_hit && load_claim(tested.object[px], tested.prim[px], d, t, a);
  const bool b_valid = b_hit && load_claim(reference.object[px], reference.prim[px], d, t, b);
  bool tie = false;
  crack = false;
  if (a_hit == a_valid && b_hit == b_valid) {
    const Claim* near = &a;
    const Claim* other = &b;
    if (a_hit && b_hit) {
      tie = same_depth(a.hit, b.hit, m_tolerance);
      if (b.hit.z < a.hit.z) std::swap(near, other);
    } else if (b_hit) {
      std::swap(near, other);
    }
    // A tie needs both sides to hit something: the tolerances absorb rounding in
    // *which* surface a ray sees, never whether it sees one. A pixel one side calls background
    // is real whatever its depth or edge margin (a scene beyond float's range once made 18.5%
    // of a frame such "ties" and passed); the crack count still says why.
    if (!tie && near->hit.near_edges != 0) {
      crack = leaks_through_crack(*near, *other, d, t);
      tie = !crack && a_hit && b_hit;
    }
  }
  return tie ? PixelClass::kTie : PixelClass::kReal;
}

void FrameComparator::add_shadow_mismatches(const Frame& tested, const Frame& reference,
                                            FrameDiff& diff) {
  const ShadowDiff shadows = compare_shadows(m_scene, m_lights, tested, reference);
  diff.shadow_lights = shadows.lights;
  for (size_t px = 0; px < diff.pixels.size(); ++px) {
    if (shadows.pixels[px] < 0 || diff.pixels[px] != PixelClass::kEqual) continue;
    const bool tie = shadows.pixels[px] == int8_t(ShadowClass::kTie);
    diff.pixels[px] = tie ? PixelClass::kTie : PixelClass::kReal;
    ++(tie ? diff.mismatch_tie : diff.mismatch_real);
  }
}

FrameDiff FrameComparator::compare(const Frame& tested, const Frame& reference) {
  if (tested.width != reference.width || tested.height != reference.height ||
      tested.pixel_count() != reference.pixel_count())
    throw std::invalid_argument("image diff: the frames differ in size");
  if (tested.time != reference.time)
    throw std::invalid_argument("image diff: the frames differ in time");
  FrameDiff diff;
  diff.width = tested.width;
  diff.height = tested.height;
  diff.time = tested.time;
  diff.pixels.resize(tested.pixel_count());
  const PixelRays image{tested.width, tested.height};
  for (int j = 0; j < tested.height; ++j)
    for (int i = 0; i < tested.width; ++i) {
      const size_t px = tested.index(i, j);
      const bool a_hit = tested.object[px] != kNoHit, b_hit = reference.object[px] != kNoHit;
      PixelClass& result = diff.pixels[px];
      if (!a_hit && !b_hit) {
        result = PixelClass::kBackground;
        continue;
      }
      if (a_hit && b_hit && tested.object[px] == reference.object[px] &&
          tested.prim[px] == reference.prim[px]) {
        result = PixelClass::kEqual;
        continue;
      }
      bool is_crack = false;
      result = judge_mismatch(tested, reference, px, image.direction(i, j), is_crack);
      ++(result == PixelClass::kTie ? diff.mismatch_tie : diff.mismatch_real);
      if (is_crack) ++diff.cracks;
    }
  add_shadow_mismatches(tested, reference, diff);
  return diff;
}

std::optional<double> ColorError::psnr() const {
  if (mse == 0) return std::nullopt;
  return 10.0 * std::log10(1.0 / mse);
}

ColorError compare_colors(const Frame& a, const Frame& b, const std::vector<uint8_t>* aside) {
  if (a.width != b.width || a.height != b.height || a.color.size() != b.color.size() ||
      (aside && aside->size() != a.color.size()))
    throw std::invalid_argument("image diff: the frames differ in size");
  ColorError error;
  double sum = 0;
  size_t counted = 0;
  for (size_t p = 0; p < a.color.size(); ++p) {
    if (aside && (*aside)[p]) continue;
    ++counted;
    for (int c = 0; c < 3; ++c) {
      const double e = double(a.color[p][c]) - double(b.color[p][c]);
      sum += e * e;
      error.max_error = std::max(error.max_error, std::abs(e));
    }
  }
  error.mse = counted == 0 ? 0.0 : sum / double(3 * counted);
  return error;
}

void write_heat_map(const FrameDiff& diff, const std::string& path, const Frame* context) {
  if (context && (context->width != diff.width || context->height != diff.height))
    context = nullptr;
  cv::Mat image(diff.height, diff.width, CV_8UC3);
  for (int j = 0; j < diff.height; ++j)
    for (int i = 0; i < diff.width; ++i) {
      const size_t p = size_t(j) * size_t(diff.width) + size_t(i);
      cv::Vec3b bgr;
      // Dim grey (at most 40% of full scale) keeps the yellow and red the brightest pixels.
      const auto underlay = [&](uint8_t plain) -> cv::Vec3b {
        if (!context) return {plain, plain, plain};
        const Color& c = context->color[p];
        const float luminance =
            std::clamp(0.2126f * c.x() + 0.7152f * c.y() + 0.0722f * c.z(), 0.0f, 1.0f);
        const auto grey = uint8_t(std::lround(20.0f + 80.0f * std::sqrt(luminance)));
        return {grey, grey, grey};
      };
      switch (diff.pixels[p]) {
        case PixelClass::kBackground:
          bgr = underlay(48);
          break;
        case PixelClass::kEqual:
          bgr = underlay(0);
          break;
        case PixelClass::kTie:
          bgr = {0, 255, 255};
          break;
        case PixelClass::kReal:
          bgr = {0, 0, 255};
          break;
      }
      image.at<cv::Vec3b>(j, i) = bgr;
    }
  bool written = false;
  try {
    written = cv::imwrite(path, image);
  } catch (const cv::Exception& e) {
    throw InputError(path, std::string("cannot write the heat map: ") + e.what());
  }
  if (!written) throw InputError(path, "cannot write the heat map");
}

FrameDiffSummary summarize(size_t frame, const FrameDiff& diff) {
  FrameDiffSummary line;
  line.frame = frame;
  line.time = diff.time;
  line.pixels = diff.pixel_count();
  line.mismatch_real = diff.mismatch_real;
  line.mismatch_tie = diff.mismatch_tie;
  line.cracks = diff.cracks;
  line.shadow_lights = diff.shadow_lights;
  return line;
}

void DiffSummary::add(FrameDiffSummary line) {
  ++frames;
  pixels += line.pixels;
  mismatch_real += line.mismatch_real;
  mismatch_tie += line.mismatch_tie;
  cracks += line.cracks;
  shadow_lights.resize(std::max(shadow_lights.size(), line.shadow_lights.size()));
  for (size_t l = 0; l < line.shadow_lights.size(); ++l) {
    shadow_lights[l].real += line.shadow_lights[l].real;
    shadow_lights[l].tie += line.shadow_lights[l].tie;
  }
  per_frame.push_back(std::move(line));
}

size_t DiffSummary::max_frame_real() const {
  size_t most = 0;
  for (const FrameDiffSummary& line : per_frame) most = std::max(most, line.mismatch_real);
  return most;
}

void DiffSummary::print(std::ostream& out) const {
  char buffer[256];
  out << "diff " << scene << ": " << tested << " against " << reference << "\n";
  std::snprintf(buffer, sizeof buffer, "%6s %10s %9s %9s %7s %9s %9s  %s\n", "frame", "time",
                "real", "tie", "cracks", "psnr_dB", "max_err", "heat map");
  out << buffer;
  for (const FrameDiffSummary& line : per_frame) {
    std::string psnr = "-", max_error = "-";
    if (line.color) {
      const std::optional<double> value = line.color->psnr();
      std::snprintf(buffer, sizeof buffer, "%.2f", value.value_or(0.0));
      psnr = value ? buffer : "inf";
      std::snprintf(buffer, sizeof buffer, "%.4f", line.color->max_error);
      max_error = buffer;
    }
    std::snprintf(buffer, sizeof buffer, "%6zu %10.5f %9zu %9zu %7zu %9s %9s  %s\n", line.frame,
                  line.time, line.mismatch_real, line.mismatch_tie, line.cracks, psnr.c_str(),
                  max_error.c_str(), line.heat_map.empty() ? "-" : line.heat_map.c_str());
    out << buffer;
  }
  std::snprintf(buffer, sizeof buffer,
                "total: %zu frames, %zu pixels, %zu real mismatches (%.4f%%), %zu ties (%.4f%%), "
                "%zu cracks\n",
                frames, pixels, mismatch_real,
                pixels ? 100.0 * double(mismatch_real) / double(pixels) : 0.0, mismatch_tie,
                pixels ? 100.0 * double(mismatch_tie) / double(pixels) : 0.0, cracks);
  out << buffer;
  for (size_t l = 0; l < shadow_lights.size(); ++l) {
    std::snprintf(buffer, sizeof buffer, "shadows of light %zu: %zu real mismatches, %zu ties\n", l,
                  shadow_lights[l].real, shadow_lights[l].tie);
    out << buffer;
  }
}

namespace {

nlohmann::json shadow_json(const std::vector<LightMismatches>& lights) {
  nlohmann::json result = nlohmann::json::array();
  for (size_t l = 0; l < lights.size(); ++l)
    result.push_back(
        {{"light", l}, {"mismatch_real", lights[l].real}, {"mismatch_tie", lights[l].tie}});
  return result;
}

}  // namespace

std::string DiffSummary::to_json() const {
  nlohmann::json lines = nlohmann::json::array();
  for (const FrameDiffSummary& line : per_frame) {
    nlohmann::json entry = {
        {"frame", line.frame},
        {"time", line.time},
        {"pixels", line.pixels},
        {"mismatch_real", line.mismatch_real},
        {"mismatch_tie", line.mismatch_tie},
        {"cracks", line.cracks},
        {"psnr", nullptr},
        {"max_error", nullptr},
        {"heat_map", line.heat_map.empty() ? nlohmann::json() : nlohmann::json(line.heat_map)}};
    if (!line.shadow_lights.empty()) entry["shadows"] = shadow_json(line.shadow_lights);
    if (line.color) {
      if (const std::optional<double> psnr = line.color->psnr()) entry["psnr"] = *psnr;
      entry["max_error"] = line.color->max_error;
    }
    lines.push_back(std::move(entry));
  }
  nlohmann::json summary = {{"scene", scene},
                            {"tested", tested},
                            {"reference", reference},
                            {"frames", frames},
                            {"pixels", pixels},
                            {"mismatch_real", mismatch_real},
                            {"mismatch_tie", mismatch_tie},
                            {"cracks", cracks},
                            {"per_frame", std::move(lines)}};
  if (!shadow_lights.empty()) summary["shadows"] = shadow_json(shadow_lights);
  return summary.dump(2) + "\n";
}

void DiffSummary::write_json(const std::string& path) const {
  write_file_atomically(path, to_json());
}

}  // namespace kinray
