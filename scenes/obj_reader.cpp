#include "scenes/obj_reader.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string_view>
#include <vector>

#include "util/input_error.h"

namespace kinray {
namespace {

/// A `v` line's value: a number in full (an optional leading '+'), or nothing.
std::optional<double> obj_number(std::string_view token) {
  const char* begin = token.data() + (token.size() > 1 && token[0] == '+' ? 1 : 0);
  double value = 0;
  const auto [end, error] = std::from_chars(begin, token.data() + token.size(), value);
  if (error != std::errc() || end != token.data() + token.size()) return std::nullopt;
  return value;
}

/// A part while the file is read: its faces in the file's global vertex numbering.
struct RawPart {
  std::string name;
  std::vector<Triangle> triangles;
};

class ObjParser {
 public:
  ObjParser(const std::string& source) : m_source(source) { m_parts.push_back({}); }

  void line(std::string_view text, size_t number) {
    m_line = number;
    const std::vector<std::string_view> w = split_words(text);
    if (w.empty() || w[0][0] == '#') return;
    if (w[0] == "v")
      vertex(w);
    else if (w[0] == "f")
      face(w);
    else if (w[0] == "o" || w[0] == "g")
      select_part(w);
  }

  MeshFile finish() const;

 private:
  std::string where() const { return m_source + ":" + std::to_string(m_line); }
  [[noreturn]] void fail(const std::string& problem) const { throw InputError(where(), problem); }

  void vertex(const std::vector<std::string_view>& w) {
    if (w.size() < 4 || w.size() > 8)
      fail("a 'v' line needs x y z (optionally w, or a colour r g b [a]), got " +
           std::to_string(w.size() - 1) + " values");
    static const char* const kAxes[3] = {"x", "y", "z"};
    Vec3 p;
    for (size_t a = 0; a < w.size() - 1; ++a) {
      const std::string_view token = w[a + 1];
      const std::optional<double> value = obj_number(token);
      if (!value) fail("expected a number, got '" + std::string(token.substr(0, 40)) + "'");
      if (a < 3) {
        check_mesh_coordinate(*value, kAxes[a], where());
        p[int(a)] = *value;
      }
    }
    if (m_positions.size() >= size_t(UINT32_MAX)) fail("too many vertices for 32-bit indices");
    m_positions.push_back(p);
  }

  /// The vertex of one corner (i, i/t, i//n, i/t/n), 0-based in the file's numbering.
  uint32_t corner(std::string_view token) const {
    const std::string_view index = token.substr(0, token.find('/'));
    int64_t value = 0;
    const auto [end, error] = std::from_chars(index.data(), index.data() + index.size(), value);
    if (error != std::errc() || end != index.data() + index.size() || index.empty())
      fail("expected a vertex index (i, i/t, i//n or i/t/n), got '" +
           std::string(token.substr(0, 40)) + "'");
    const int64_t count = int64_t(m_positions.size());
    const int64_t resolved = value < 0 ? count + value : value - 1;
    if (value == 0 || resolved < 0 || resolved >= count)
      fail("vertex index " + std::string(index) + " out of range (" + std::to_string(count) +
           " vertices so far)");
    return uint32_t(resolved);
  }

  void face(const std::vector<std::string_view>& w) {
    if (w.size() < 4) fail("a face needs at least 3 corners, got " + std::to_string(w.size() - 1));
    m_polygon.clear();
    for (size_t k = 1; k < w.size(); ++k) m_polygon.push_back(corner(w[k]));
    append_fan(m_polygon, m_parts[m_current].triangles);
  }

  void select_part(const std::vector<std::string_view>& w) {
    std::string name;
    for (size_t k = 1; k < w.size(); ++k) name += (k > 1 ? " " : "") + std::string(w[k]);
    for (size_t p = 0; p < m_parts.size(); ++p)
      if (m_parts[p].name == name) {
        m_current = p;
        return;
      }
    m_parts.push_back({name, {}});
    m_current = m_parts.size() - 1;
  }

  const std::string& m_source;
  size_t m_line = 0;
  std::vector<Vec3> m_positions;
  std::vector<RawPart> m_parts;  ///< the first is the unnamed part before any o or g
  size_t m_current = 0;
  std::vector<uint32_t> m_polygon;
};

MeshFile ObjParser::finish() const {
  MeshFile file;
  for (const RawPart& raw : m_parts) {
    if (raw.triangles.empty()) continue;
    std::vector<uint32_t> used;
    used.reserve(raw.triangles.size() * 3);
    for (const Triangle& t : raw.triangles) used.insert(used.end(), t.begin(), t.end());
    std::sort(used.begin(), used.end());
    used.erase(std::unique(used.begin(), used.end()), used.end());
    MeshPart part;
    part.name = raw.name;
    part.positions.reserve(used.size());
    for (uint32_t v : used) part.positions.push_back(m_positions[v]);
    part.triangles.reserve(raw.triangles.size());
    const auto local = [&](uint32_t v) {
      return uint32_t(std::lower_bound(used.begin(), used.end(), v) - used.begin());
    };
    for (const Triangle& t : raw.triangles)
      part.triangles.push_back({local(t[0]), local(t[1]), local(t[2])});
    file.parts.push_back(std::move(part));
  }
  if (file.parts.empty()) throw InputError(m_source, "has no faces");
  return file;
}

}  // namespace

MeshFile parse_obj(std::string_view bytes, const std::string& source) {
  ObjParser parser(source);
  size_t offset = 0, number = 0;
  while (offset < bytes.size()) {
    const size_t newline = std::min(bytes.find('\n', offset), bytes.size());
    parser.line(bytes.substr(offset, newline - offset), ++number);
    offset = newline + 1;
  }
  return parser.finish();
}

MeshFile read_obj(const std::string& path) {
  return parse_obj(read_mesh_bytes(path), path);
}

void check_obj_file(const std::string& path) {
  std::string extension = std::filesystem::path(path).extension().string();
  for (char& c : extension) c = char(std::tolower(static_cast<unsigned char>(c)));
  if (extension != ".obj") return;
  std::ifstream file(path, std::ios::binary);
  static const char* const kAxes[3] = {"x", "y", "z"};
  size_t number = 0;
  for (std::string text; std::getline(file, text);) {
    ++number;
    const std::vector<std::string_view> w = split_words(text);
    if (w.size() < 4 || w[0] != "v") continue;
    for (size_t a = 0; a < 3; ++a)
      // Only what parses as a number is judged here; a malformed token is assimp's to report.
      if (const std::optional<double> value = obj_number(w[a + 1]))
        check_mesh_coordinate(*value, kAxes[a], path + ":" + std::to_string(number));
  }
}

}  // namespace kinray
