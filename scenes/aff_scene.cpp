#include "scenes/aff_scene.h"

#include <cctype>
#include <cmath>
#include <cstdio>
#include <map>
#include <memory>

#include "scenes/aff_parser.h"
#include "util/input_error.h"
#include "util/warning.h"

namespace kinray {
namespace {

/// One transform above a shape: a fixed matrix, or an animation's matrix at each sample time.
struct Link {
  Eigen::Affine3d fixed = Eigen::Affine3d::Identity();
  const std::vector<Eigen::Affine3d>* animated = nullptr;
};

/// Walks the transform tree and turns every shape into an object.
class SceneBuilder {
 public:
  SceneBuilder(const AffDocument& document, std::vector<double> times, Scene& scene)
      : m_document(document), m_times(std::move(times)), m_scene(scene) {}

  void visit(const AffNode& node, std::vector<Link> chain) {
    if (!node.animation.empty()) {
      chain.push_back({Eigen::Affine3d::Identity(), &matrices(node)});
    } else if (!chain.empty() && !chain.back().animated) {
      chain.back().fixed = chain.back().fixed * node.transform;  // fold consecutive static ones
    } else {
      chain.push_back({node.transform, nullptr});
    }
    std::shared_ptr<const std::vector<Eigen::Affine3d>> transforms;  // the chain's, once per node
    for (const AffShape& shape : node.shapes) add_object(shape, chain, transforms);
    for (const auto& child : node.children) visit(*child, chain);
  }

 private:
  const std::vector<Eigen::Affine3d>& matrices(const AffNode& node) {
    const auto cached = m_matrices.find(node.animation);
    if (cached != m_matrices.end()) return cached->second;
    const auto found = m_document.animations.find(node.animation);
    std::vector<Eigen::Affine3d>& samples = m_matrices[node.animation];
    if (found == m_document.animations.end()) {
      // BART's GetMatrix: an animation without keyframes is the identity (Robot1.aff's grip_lift1).
      warn(node.where + ": the animated transform '" + node.animation +
           "' has no keyframes; it stays the identity");
      samples.assign(m_times.size(), Eigen::Affine3d::Identity());
      return samples;
    }
    for (double t : m_times) samples.push_back(found->second.matrix(t));
    return samples;
  }

  static Eigen::Affine3d product(const std::vector<Link>& chain, size_t key) {
    Eigen::Affine3d m = Eigen::Affine3d::Identity();
    for (const Link& link : chain) m = m * (link.animated ? (*link.animated)[key] : link.fixed);
    return m;
  }

  /// The shape's own (tpa) positions at t: linear between its keys, clamped outside.
  static std::vector<Vec3> shape_positions(const AffShape& shape, double t) {
    const auto& times = shape.key_times;
    if (times.size() == 1 || t <= times.front()) return shape.key_positions.front();
    if (t >= times.back()) return shape.key_positions.back();
    const size_t k = size_t(std::upper_bound(times.begin(), times.end(), t) - times.begin()) - 1;
    const double alpha = (t - times[k]) / (times[k + 1] - times[k]);
    std::vector<Vec3> positions = shape.key_positions[k];
    for (size_t v = 0; v < positions.size(); ++v)
      positions[v] += alpha * (shape.key_positions[k + 1][v] - positions[v]);
    return positions;
  }

  /// `transforms` caches the chain's transform at every key, shared by the objects of one node.
  void add_object(const AffShape& shape, const std::vector<Link>& chain,
                  std::shared_ptr<const std::vector<Eigen::Affine3d>>& transforms) {
    Object object;
    object.name = shape.where;
    object.triangles = shape.triangles;
    object.uvs = shape.uvs;
    object.material = shape.material;
    const bool animated =
        std::any_of(chain.begin(), chain.end(), [](const Link& l) { return l.animated; });
    auto transformed = [](const Eigen::Affine3d& m, std::vector<Vec3> positions) {
      for (Vec3& p : positions) p = RigidKeys::transform(m, p);
      return positions;
    };
    if (!animated) {
      // Static transforms only: the shape's own keys (one, or a tpa's), transformed once.
      const Eigen::Affine3d m = product(chain, 0);
      object.key_times = shape.key_times;
      for (const auto& positions : shape.key_positions)
        object.key_positions.push_back(transformed(m, positions));
    } else if (shape.key_times.size() == 1) {
      // A still shape under animated transforms moves rigidly: its positions and the chain's
      // transform at each key (the robots' parts, which explicit keys would hold 800 times).
      if (!transforms) {
        auto matrices = std::make_shared<std::vector<Eigen::Affine3d>>(m_times.size());
        for (size_t k = 0; k < m_times.size(); ++k) (*matrices)[k] = product(chain, k);
        transforms = std::move(matrices);
      }
      object.key_times = m_times;
      object.rigid = RigidKeys{shape.key_positions.front(), transforms};
    } else {
      object.key_times = m_times;
      for (size_t k = 0; k < m_times.size(); ++k)
        object.key_positions.push_back(
            transformed(product(chain, k), shape_positions(shape, m_times[k])));
    }
    m_scene.objects.push_back(std::move(object));
  }

  const AffDocument& m_document;
  std::vector<double> m_times;
  Scene& m_scene;
  std::map<std::string, std::vector<Eigen::Affine3d>> m_matrices;
};

/// BART's camera: the view, with position and orientation from the keyframes named "camera"
/// when they exist (GetCamera: the view direction is -z of the rotation, up is its y).
Camera build_camera(const AffDocument& document, const std::vector<double>& times) {
  const AffView& view = document.view;
  const auto found = document.animations.find("camera");
  Camera camera;
  if (found == document.animations.end() ||
      (!found->second.translation && !found->second.rotation)) {
    camera.keys = {Camera::look_at(times.front(), view.from, view.at, view.up, view.angle_degrees)};
    return camera;
  }
  const AffAnimation& animation = found->second;
  camera.keys.clear();
  for (double t : times) {
    const Vec3 eye = animation.translation ? animation.translation->at(t) : view.from;
    Vec3 direction = view.at - view.from, up = view.up;
    if (animation.rotation) {
      const Eigen::Matrix3d r = animation.rotation->at(t).toRotationMatrix();
      direction = -r.col(2);
      up = r.col(1);
    }
    camera.keys.push_back(Camera::look_at(t, eye, eye + direction, up, view.angle_degrees));
  }
  return camera;
}

}  // namespace

bool is_aff_file(const std::string& path) {
  if (path.size() < 4) return false;
  std::string extension = path.substr(path.size() - 4);
  for (char& c : extension) c = char(std::tolower(static_cast<unsigned char>(c)));
  return extension == ".aff";
}

std::vector<double> aff_sample_times(const AffRange& range, double keyrate) {
  std::vector<double> times;
  if (keyrate > 0) {
    // k / rate rounds: stop a hair before the end so that the end is not doubled.
    const double span = range.end - range.start;
    for (double k = 0; k / keyrate < span * (1 - 1e-12); k += 1)
      times.push_back(range.start + k / keyrate);
    times.push_back(range.end);
    return times;
  }
  const int n = range.frames;
  for (int i = 0; i < n; ++i)
    times.push_back(n == 1 ? range.start : range.start + (range.end - range.start) * i / (n - 1));
  if (n > 1) times.back() = range.end;
  return times;
}

Scene build_aff_scene(const AffDocument& document, const std::string& source, double keyrate) {
  if (!document.view.given)
    throw InputError(source, "the scene has no view (v from ... resolution)");
  const bool animates = !document.animations.empty() || [&] {
    std::vector<const AffNode*> stack = {&document.root};
    while (!stack.empty()) {
      const AffNode* node = stack.back();
      stack.pop_back();
      if (!node->animation.empty()) return true;
      for (const AffShape& shape : node->shapes)
        if (shape.key_times.size() > 1) return true;
      for (const auto& child : node->children) stack.push_back(child.get());
    }
    return false;
  }();
  if (animates && !document.range)
    throw InputError(source,
                     "the scene is animated but gives no animation range (a start end frames)");
  const AffRange range = document.range.value_or(AffRange{0, 1, 1});

  Scene scene;
  scene.name = std::filesystem::path(source).stem().string();
  scene.time_begin = range.start;
  scene.time_end = range.end;
  scene.image_width = document.view.width;
  scene.image_height = document.view.height;
  scene.frame_count = document.range ? range.frames : 0;
  scene.materials = document.materials;
  scene.textures = document.textures;
  scene.lights = document.lights;
  const std::vector<double> times = aff_sample_times(range, keyrate);
  scene.camera = build_camera(document, times);
  SceneBuilder(document, times, scene).visit(document.root, {});
  if (scene.objects.empty()) throw InputError(source, "the scene has no triangles");
  return scene;
}

Scene load_aff(const std::filesystem::path& path, double keyrate) {
  const AffDocument document = parse_aff(path);
  for (const std::string& warning : document.warnings) warn(warning);
  return build_aff_scene(document, path.string(), keyrate);
}

}  // namespace kinray
