#include "scenes/aff_parser.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>
#include <utility>

#include "scenes/aff_reader.h"
#include "scenes/aff_shapes.h"
#include "scenes/ppm_texture.h"
#include "util/input_error.h"

namespace kinray {
namespace {

namespace fs = std::filesystem;

constexpr int kMaxIncludeDepth = 64;
constexpr int kMaxKeys = 10'000'000;

Vec3 read_vec3(AffReader& in, const char* what) {
  double xyz[3];
  in.numbers(xyz, 3, what);
  return {xyz[0], xyz[1], xyz[2]};
}

Color read_color(AffReader& in, const char* what) {
  const Vec3 c = read_vec3(in, what);
  return c.cast<float>();
}

bool is_number(std::string_view token) {
  return !token.empty() && (std::isdigit(static_cast<unsigned char>(token[0])) || token[0] == '-' ||
                            token[0] == '+' || token[0] == '.');
}

/// Scale, then rotation about an axis by degrees, then translation (T * R * S), as `xs` says.
Eigen::Affine3d static_transform(const Vec3& scale, const Vec3& axis, double degrees,
                                 const Vec3& translation) {
  Eigen::Affine3d m = Eigen::Affine3d::Identity();
  m.translate(translation);
  if (axis.norm() > 0) m.rotate(Eigen::AngleAxisd(degrees * M_PI / 180.0, axis.normalized()));
  m.scale(scale);
  return m;
}

class AffParser {
 public:
  AffDocument parse(const fs::path& file) {
    m_document.materials = {Material{"default"}};
    parse_file(file, m_document.root, 0);
    return std::move(m_document);
  }

 private:
  void parse_file(const fs::path& file, AffNode& node, int depth) {
    AffReader in(file);
    parse_block(in, node, false, depth);
  }

  /// Elements up to the end of the file, or up to the '}' that closes a transform.
  void parse_block(AffReader& in, AffNode& node, bool closed_by_brace, int depth) {
    while (!in.at_end()) {
      if (in.peek() == "}") {
        if (!closed_by_brace) {
          (void)in.word("'}'");
          in.fail("'}' without a matching '{'");
        }
        (void)in.word("'}'");
        return;
      }
      parse_element(in, node, depth);
    }
    if (closed_by_brace) {
      (void)in.word("'}' (closing a transform)");  // fails with the end of the file
    }
  }

  void parse_element(AffReader& in, AffNode& node, int depth) {
    const std::string keyword = in.word("an element");
    if (keyword == "v") return parse_view(in);
    if (keyword == "b")
      return void(m_document.background = read_color(in, "the background colour"));
    if (keyword == "am") return void(m_document.ambient = read_color(in, "the ambient colour"));
    if (keyword == "l") return parse_light(in);
    if (keyword == "fm" || keyword == "f") return parse_fill(in, keyword == "fm");
    if (keyword == "m") return add_shape(in, node, read_mesh(in));
    if (keyword == "p" || keyword == "pp")
      return add_shape(in, node, read_polygon(in, keyword == "pp"));
    if (keyword == "tt" || keyword == "ttp")
      return add_shape(in, node, read_textured_triangle(in, keyword == "ttp"));
    if (keyword == "tpa") return add_shape(in, node, read_animated_triangle(in));
    if (keyword == "c") return add_shape(in, node, read_cone(in));
    if (keyword == "s") return add_shape(in, node, read_sphere(in));
    if (keyword == "i") return parse_include(in, node, depth);
    if (keyword == "d")
      return void(m_detail = in.integer("the detail level", -1'000'000, 1'000'000));
    if (keyword == "xs" || keyword == "x") return parse_transform(in, node, keyword == "xs", depth);
    if (keyword == "k") return parse_keyframes(in);
    if (keyword == "a") return parse_range(in);
    if (keyword == "la") in.fail("animated lights (la) are not supported");
    in.fail("unknown element '" + keyword + "'");
  }

  void parse_view(AffReader& in) {
    AffView& view = m_document.view;
    in.expect("from");
    view.from = read_vec3(in, "the eye position");
    in.expect("at");
    view.at = read_vec3(in, "the point looked at");
    in.expect("up");
    view.up = read_vec3(in, "the up vector");
    in.expect("angle");
    view.angle_degrees = in.number("the field of view angle");
    if (!(view.angle_degrees > 0 && view.angle_degrees < 180))
      in.fail("the field of view angle must lie in (0, 180) degrees");
    in.expect("hither");
    view.hither = in.number("the hither distance");
    in.expect("resolution");
    view.width = in.integer("the image width", 1, 16384);
    view.height = in.integer("the image height", 1, 16384);
    if ((view.at - view.from).norm() == 0) in.fail("the view's from and at coincide");
    if (view.up.cross(view.at - view.from).norm() == 0)
      in.fail("the view's up vector is parallel to the viewing direction");
    view.given = true;
  }

  void parse_light(AffReader& in) {
    Light light;
    light.position = read_vec3(in, "the light position");
    if (is_number(in.peek())) light.color = read_color(in, "the light colour");
    m_document.lights.push_back(light);
  }

  /// `fm` ambient diffuse specular (RGB each) phong transmittance ior, or NFF's `f` r g b Kd Ks
  /// shine T ior: what kinray shades with is the diffuse colour.
  void parse_fill(AffReader& in, bool extended) {
    if (extended) {
      (void)read_color(in, "the ambient colour");
      m_fill = read_color(in, "the diffuse colour");
      (void)read_color(in, "the specular colour");
      double rest[3];
      in.numbers(rest, 3, "the phong exponent, transmittance and index of refraction");
    } else {
      m_fill = read_color(in, "the fill colour");
      double rest[5];
      in.numbers(rest, 5, "Kd, Ks, shine, T and the index of refraction");
      m_fill *= float(rest[0]);
    }
    m_fill = m_fill.cwiseMax(0.0f).cwiseMin(1.0f);
    m_fill_where = in.where();
    ++m_fill_index;
  }

  void add_shape(AffReader& in, AffNode& node, AffShapeRead read) {
    read.shape.material = material(in, read.texture, read.shape.where);
    if (read.shape.key_positions.empty() || read.shape.triangles.empty()) return;
    node.shapes.push_back(std::move(read.shape));
  }

  /// The material of the current fill with `texture` (a file name beside the current file).
  uint32_t material(const AffReader& in, const std::string& texture, const std::string& where) {
    int texture_index = -1;
    std::string texture_path;
    if (!texture.empty()) {
      const fs::path path = in.file().parent_path() / texture;
      texture_path = path.lexically_normal().string();
      texture_index = load_texture(path, texture_path, where);
    }
    if (m_fill_index < 0 && texture_index < 0) return 0;
    const auto key = std::make_pair(m_fill_index, texture_index);
    const auto found = m_materials.find(key);
    if (found != m_materials.end()) return found->second;
    Material material;
    material.name = m_fill_index < 0 ? "default" : "fm at " + m_fill_where;
    if (m_fill_index >= 0) material.base_color = m_fill;
    if (texture_index >= 0) {
      material.texture = texture_index;
      material.name += " with " + fs::path(texture_path).filename().string();
    }
    const uint32_t index = uint32_t(m_document.materials.size());
    m_document.materials.push_back(material);
    m_materials.emplace(key, index);
    return index;
  }

  int load_texture(const fs::path& path, const std::string& key, const std::string& where) {
    const auto found = m_textures.find(key);
    if (found != m_textures.end()) return found->second;
    int index = -1;
    std::error_code error;
    if (fs::is_regular_file(path, error)) {
      index = int(m_document.textures.size());
      try {
        m_document.textures.push_back(read_ppm(path));
      } catch (const InputError& bad) {
        // The PPM's own problem, placed at the element that names the texture.
        throw InputError(where, "texture '" + key +
                                    "': " + std::string(bad.what()).substr(bad.where().size() + 2));
      }
    } else {
      m_document.warnings.push_back(where + ": texture '" + key +
                                    "' not found; its shapes keep their material's colour");
    }
    m_textures.emplace(key, index);
    return index;
  }

  void parse_include(AffReader& in, AffNode& node, int depth) {
    const int detail = in.integer("the include's detail level", -1'000'000, 1'000'000);
    const std::string name = in.word("the file to include");
    if (detail > m_detail) return;  // BART: files above the scene's detail level are skipped
    const fs::path path = in.file().parent_path() / name;
    std::error_code error;
    if (!fs::is_regular_file(path, error))
      in.fail("cannot include '" + path.string() + "': no such file");
    if (depth + 1 > kMaxIncludeDepth)
      in.fail("includes nest deeper than " + std::to_string(kMaxIncludeDepth) +
              " files (an include cycle?)");
    parse_file(path, node, depth + 1);
  }

  void parse_transform(AffReader& in, AffNode& node, bool is_static, int depth) {
    auto child = std::make_unique<AffNode>();
    child->where = in.where();
    if (is_static) {
      const Vec3 scale = read_vec3(in, "the scale");
      const Vec3 axis = read_vec3(in, "the rotation axis");
      const double degrees = in.number("the rotation angle");
      const Vec3 translation = read_vec3(in, "the translation");
      if (axis.norm() == 0 && degrees != 0) in.fail("the rotation axis is zero");
      child->transform = static_transform(scale, axis, degrees, translation);
    } else {
      child->animation = in.word("the name of the animated transform");
      if (child->animation == "{") in.fail("the animated transform has no name");
    }
    in.expect("{");
    parse_block(in, *child, true, depth);
    node.children.push_back(std::move(child));
  }

  std::vector<SplineKey> read_keys(AffReader& in, const std::string& part, int count) {
    std::vector<SplineKey> keys(static_cast<size_t>(count));
    const std::string where = in.where();
    for (SplineKey& key : keys) {
      key.time = in.number("a key time");
      key.value = read_vec3(in, part == "rot" ? "the rotation axis" : "the key value");
      if (part == "rot") key.angle_degrees = in.number("the rotation angle");
      key.tension = in.number("the tension");
      key.continuity = in.number("the continuity");
      key.bias = in.number("the bias");
    }
    // BART's reference code accepts keys out of order (Robot1.aff has one: 48 then 42) and
    // evaluates them as they stand, so kinray renders such a file as BART does, but says so (the
    // JSON reader, with no such files to honour, refuses them); only a zero span of two pieces
    // would divide by zero.
    for (size_t i = 2; i < keys.size(); ++i)
      if (keys[i].time == keys[i - 2].time)
        in.fail("three " + part + " keys in a row share the time " + std::to_string(keys[i].time));
    for (size_t i = 1; i < keys.size(); ++i)
      if (!(keys[i].time > keys[i - 1].time)) {
        std::ostringstream line;
        line << where << ": " << part << " key " << i << " (t=" << keys[i].time << ") "
             << (keys[i].time == keys[i - 1].time ? "repeats" : "comes before")
             << " the time of the key before it (t=" << keys[i - 1].time
             << "); played in file order, as BART's reference code does";
        m_document.warnings.push_back(line.str());
        break;
      }
    return keys;
  }

  void parse_keyframes(AffReader& in) {
    const std::string name = in.word("the name of the animation");
    if (name == "{") in.fail("the keyframes have no name");
    AffAnimation animation;
    animation.where = in.where();
    in.expect("{");
    while (in.peek() != "}") {
      const std::string part = in.word("transl, rot, scale or '}'");
      if (part == "visibility") in.fail("visibility keyframes are not supported");
      if (part != "transl" && part != "rot" && part != "scale")
        in.fail("unknown keyframe type '" + part + "' (expected transl, rot or scale)");
      const int count = in.integer("the number of keys", 0, kMaxKeys);
      if (count < 4)
        in.fail("a " + part + " spline needs at least 4 keys, got " + std::to_string(count));
      const bool twice = part == "transl"  ? animation.translation.has_value()
                         : part == "scale" ? animation.scale.has_value()
                                           : animation.rotation.has_value();
      if (twice) in.fail("the keyframes of '" + name + "' give " + part + " twice");
      const std::vector<SplineKey> keys = read_keys(in, part, count);
      for (const SplineKey& key : keys) animation.key_times.push_back(key.time);
      if (part == "transl") animation.translation.emplace(keys);
      if (part == "scale") animation.scale.emplace(keys);
      if (part == "rot") animation.rotation.emplace(keys);
    }
    in.expect("}");
    // A file included twice gives its keyframes twice; BART's FindAnimation takes the first.
    m_document.animations.emplace(name, std::move(animation));
  }

  void parse_range(AffReader& in) {
    AffRange range;
    range.start = in.number("the animation's start time");
    range.end = in.number("the animation's end time");
    range.frames = in.integer("the animation's frame count", 1, 1'000'000);
    if (!(range.end > range.start)) in.fail("the animation must end after it starts");
    m_document.range = range;
  }

  AffDocument m_document;
  int m_detail = 0;
  Color m_fill = Color(0.8f, 0.8f, 0.8f);
  int m_fill_index = -1;
  std::string m_fill_where;
  std::map<std::pair<int, int>, uint32_t> m_materials;  // (fill, texture) -> material
  std::map<std::string, int> m_textures;                // path -> texture index, -1: missing
};

}  // namespace

Eigen::Affine3d AffAnimation::matrix(double t) const {
  Eigen::Affine3d m = Eigen::Affine3d::Identity();
  if (translation) m.translate(translation->at(t));
  if (rotation) m.rotate(rotation->at(t));
  if (scale) m.scale(scale->at(t));
  return m;
}

AffDocument parse_aff(const std::filesystem::path& file) {
  return AffParser().parse(file);
}

}  // namespace kinray
