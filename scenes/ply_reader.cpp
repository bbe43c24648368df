#include "scenes/ply_reader.h"

#include <algorithm>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <optional>

#include "util/input_error.h"

namespace kinray {
namespace {

enum class PlyType : uint8_t { int8, uint8, int16, uint16, int32, uint32, float32, float64 };
enum class PlyFormat : uint8_t { ascii, little_endian, big_endian };

size_t type_size(PlyType type) {
  switch (type) {
    case PlyType::int8:
    case PlyType::uint8:
      return 1;
    case PlyType::int16:
    case PlyType::uint16:
      return 2;
    case PlyType::int32:
    case PlyType::uint32:
    case PlyType::float32:
      return 4;
    case PlyType::float64:
      break;
  }
  return 8;
}

bool is_integral(PlyType type) {
  return type != PlyType::float32 && type != PlyType::float64;
}

/// Both the names of the PLY paper and the sized ones (char/int8, float/float32, ...).
std::optional<PlyType> parse_type(std::string_view name) {
  static const std::pair<std::string_view, PlyType> kNames[] = {
      {"char", PlyType::int8},      {"int8", PlyType::int8},       {"uchar", PlyType::uint8},
      {"uint8", PlyType::uint8},    {"short", PlyType::int16},     {"int16", PlyType::int16},
      {"ushort", PlyType::uint16},  {"uint16", PlyType::uint16},   {"int", PlyType::int32},
      {"int32", PlyType::int32},    {"uint", PlyType::uint32},     {"uint32", PlyType::uint32},
      {"float", PlyType::float32},  {"float32", PlyType::float32}, {"double", PlyType::float64},
      {"float64", PlyType::float64}};
  for (const auto& [text, type] : kNames)
    if (text == name) return type;
  return std::nullopt;
}

struct PlyProperty {
  std::string name;
  PlyType type = PlyType::float32;  ///< of the value, or of a list's items
  bool list = false;
  PlyType count_type = PlyType::uint8;  ///< of a list's length
};

struct PlyElement {
  std::string name;
  uint64_t count = 0;
  std::vector<PlyProperty> properties;
  size_t line = 0;  ///< of its `element` line
};

struct PlyHeader {
  PlyFormat format = PlyFormat::ascii;
  std::vector<PlyElement> elements;
  size_t body = 0;       ///< byte offset of the first byte after end_header's line
  size_t body_line = 0;  ///< line number of that byte
};

/// A coordinate that no reader should take (NaN, infinite, beyond +-kMaxCoordinate): told apart
/// from the other problems so that check_ply_file can refuse it while leaving those to assimp.
class PlyCoordinateError : public InputError {
 public:
  explicit PlyCoordinateError(const InputError& error) : InputError(error) {}
};

std::string at_line(const std::string& source, size_t line) {
  return source + ":" + std::to_string(line);
}

/// Whether a header line that no PLY reader knows is an error or is passed over.
enum class UnknownLines { refuse, skip };

/// One header line (`element`, `property`, `format`, ...) applied to `header`.
void parse_header_line(const std::vector<std::string_view>& w, PlyHeader& header,
                       const std::string& where, UnknownLines unknown) {
  const auto fail = [&](const std::string& problem) { throw InputError(where, problem); };
  if (w[0] == "comment" || w[0] == "obj_info") return;
  if (w[0] == "format") {
    if (w.size() != 3 || w[2] != "1.0")
      fail("expected 'format ascii|binary_little_endian|binary_big_endian 1.0'");
    if (w[1] == "ascii")
      header.format = PlyFormat::ascii;
    else if (w[1] == "binary_little_endian")
      header.format = PlyFormat::little_endian;
    else if (w[1] == "binary_big_endian")
      header.format = PlyFormat::big_endian;
    else
      fail("unknown format '" + std::string(w[1]) + "'");
  } else if (w[0] == "element") {
    uint64_t count = 0;
    if (w.size() != 3) fail("expected 'element NAME COUNT'");
    const auto [end, error] = std::from_chars(w[2].data(), w[2].data() + w[2].size(), count);
    if (error != std::errc() || end != w[2].data() + w[2].size())
      fail("element count '" + std::string(w[2]) + "' is not a non-negative integer");
    header.elements.push_back({std::string(w[1]), count, {}, 0});
  } else if (w[0] == "property") {
    if (header.elements.empty()) fail("a property before any element");
    PlyProperty property;
    const bool list = w.size() == 5 && w[1] == "list";
    if (!list && w.size() != 3)
      fail("expected 'property TYPE NAME' or 'property list TYPE TYPE NAME'");
    const std::optional<PlyType> type = parse_type(w[list ? 3 : 1]);
    if (!type) fail("unknown property type '" + std::string(w[list ? 3 : 1]) + "'");
    property.type = *type;
    property.list = list;
    property.name = std::string(w.back());
    if (list) {
      const std::optional<PlyType> count_type = parse_type(w[2]);
      if (!count_type || !is_integral(*count_type))
        fail("a list's length type must be an integer type, got '" + std::string(w[2]) + "'");
      property.count_type = *count_type;
    }
    header.elements.back().properties.push_back(property);
  } else if (unknown == UnknownLines::refuse) {
    fail("unknown header line '" + std::string(w[0]) + "'");
  }
}

PlyHeader parse_header(std::string_view bytes, const std::string& source,
                       UnknownLines unknown = UnknownLines::refuse) {
  PlyHeader header;
  size_t offset = 0, line = 0;
  bool format_seen = false;
  while (true) {
    ++line;
    if (offset >= bytes.size())
      throw InputError(at_line(source, line), "the header ends without 'end_header'");
    const size_t newline = std::min(bytes.find('\n', offset), bytes.size());
    const std::vector<std::string_view> w = split_words(bytes.substr(offset, newline - offset));
    offset = newline + 1;
    const std::string where = at_line(source, line);
    if (line == 1) {
      if (w.size() != 1 || w[0] != "ply") throw InputError(where, "not a PLY file (no 'ply' line)");
      continue;
    }
    if (w.empty()) continue;
    if (w[0] == "end_header") break;
    format_seen |= w[0] == "format";
    parse_header_line(w, header, where, unknown);
    if (w[0] == "element") header.elements.back().line = line;
  }
  if (!format_seen) throw InputError(at_line(source, 2), "the header has no 'format' line");
  header.body = std::min(offset, bytes.size());
  header.body_line = line + 1;
  return header;
}

/// The values of the body, in order: ascii tokens or binary numbers, each checked.
class PlyBody {
 public:
  PlyBody(std::string_view bytes, const PlyHeader& header, const std::string& source)
      : m_bytes(bytes),
        m_offset(header.body),
        m_line(header.body_line),
        m_format(header.format),
        m_source(source) {}

  /// The next value as a double (every PLY type converts exactly).
  double number(PlyType type) {
    return m_format == PlyFormat::ascii ? ascii_number(type) : binary_number(type);
  }
  /// The next value as a list length or an index: a non-negative integer.
  uint64_t whole(PlyType type, const char* what) {
    const double value = number(type);
    if (!(value >= 0) || value != std::floor(value) || value >= 18446744073709551616.0)
      fail(std::string(what) + " must be a non-negative integer");
    return uint64_t(value);
  }
  /// Bytes left, for the size checks of binary lists.
  [[nodiscard]] size_t remaining() const { return m_bytes.size() - m_offset; }
  [[nodiscard]] bool ascii() const { return m_format == PlyFormat::ascii; }
  [[nodiscard]] std::string where() const {
    return ascii() ? at_line(m_source, m_line) : m_source + ": byte " + std::to_string(m_offset);
  }
  [[noreturn]] void fail(const std::string& problem) const { throw InputError(where(), problem); }

 private:
  static bool is_space(char c) {
    return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\f' || c == '\v';
  }

  std::string_view next_token() {
    const size_t line = m_line;  // an early end is reported at the last value's line
    while (m_offset < m_bytes.size() && is_space(m_bytes[m_offset])) {
      if (m_bytes[m_offset] == '\n') ++m_line;
      ++m_offset;
    }
    if (m_offset >= m_bytes.size()) {
      m_line = line;
      fail("the file ends early: more values are declared");
    }
    const size_t begin = m_offset;
    while (m_offset < m_bytes.size() && !is_space(m_bytes[m_offset])) ++m_offset;
    return m_bytes.substr(begin, m_offset - begin);
  }

  double ascii_number(PlyType type) {
    const std::string_view token = next_token();
    const char* begin = token.data() + (token.size() > 1 && token[0] == '+' ? 1 : 0);
    const char* end = token.data() + token.size();
    if (is_integral(type)) {
      int64_t value = 0;
      const auto [stop, error] = std::from_chars(begin, end, value);
      if (error != std::errc() || stop != end)
        fail("expected an integer, got '" + std::string(token.substr(0, 40)) + "'");
      return double(value);
    }
    double value = 0;
    const auto [stop, error] = std::from_chars(begin, end, value);
    if (error != std::errc() || stop != end)
      fail("expected a number, got '" + std::string(token.substr(0, 40)) + "'");
    return value;
  }

  template <typename T>
  T read_raw() {
    T value;
    std::memcpy(&value, m_bytes.data() + m_offset, sizeof(T));
    const bool swap =
        (m_format == PlyFormat::big_endian) != (std::endian::native == std::endian::big);
    if (swap) {
      unsigned char raw[sizeof(T)];
      std::memcpy(raw, &value, sizeof(T));
      for (size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(raw[i], raw[sizeof(T) - 1 - i]);
      std::memcpy(&value, raw, sizeof(T));
    }
    m_offset += sizeof(T);
    return value;
  }

  double binary_number(PlyType type) {
    if (remaining() < type_size(type)) fail("the file ends early: more values are declared");
    switch (type) {
      case PlyType::int8:
        return read_raw<int8_t>();
      case PlyType::uint8:
        return read_raw<uint8_t>();
      case PlyType::int16:
        return read_raw<int16_t>();
      case PlyType::uint16:
        return read_raw<uint16_t>();
      case PlyType::int32:
        return read_raw<int32_t>();
      case PlyType::uint32:
        return read_raw<uint32_t>();
      case PlyType::float32:
        return read_raw<float>();
      case PlyType::float64:
        break;
    }
    return read_raw<double>();
  }

  std::string_view m_bytes;
  size_t m_offset = 0;
  size_t m_line = 1;
  PlyFormat m_format;
  const std::string& m_source;
};

/// Reads a list property's items and throws them away.
void skip_list(PlyBody& body, const PlyProperty& property) {
  const uint64_t count = body.whole(property.count_type, "a list's length");
  if (!body.ascii() && count > body.remaining() / type_size(property.type))
    body.fail("a list of " + std::to_string(count) + " items runs past the end of the file");
  for (uint64_t k = 0; k < count; ++k) (void)body.number(property.type);
}

/// Fewest bytes one instance of `element` takes: binary sizes, or one character and a separator
/// per ascii value. Guards the counts of the header before anything is reserved.
uint64_t smallest_instance(const PlyElement& element, PlyFormat format) {
  uint64_t bytes = 0;
  for (const PlyProperty& p : element.properties)
    bytes += format == PlyFormat::ascii ? 2 : type_size(p.list ? p.count_type : p.type);
  return bytes;
}

/// Instances without properties take no bytes, so the file's length bounds their count
/// nothing; a reader that loops over them (assimp's does) runs for as long as the count says.
void check_has_properties(const PlyElement& element, const std::string& source) {
  if (element.properties.empty() && element.count > 0)
    throw InputError(at_line(source, element.line),
                     "declares " + std::to_string(element.count) + " " + element.name +
                         " elements but no properties for them");
}

void check_counts(const PlyHeader& header, size_t body_bytes, const std::string& source) {
  uint64_t needed = 0;
  for (const PlyElement& element : header.elements) {
    check_has_properties(element, source);
    const uint64_t each = smallest_instance(element, header.format);
    if (each > 0 && element.count > (body_bytes + 1) / each)
      throw InputError(at_line(source, element.line),
                       "declares " + std::to_string(element.count) + " " + element.name +
                           " elements, more than the " + std::to_string(body_bytes) +
                           " bytes after the header can hold");
    needed += each * element.count;
  }
  if (needed > body_bytes + 1)
    throw InputError(source, "the header declares more data than the file holds");
}

/// Index of the property `name` of `element` (not a list), or -1.
int find_scalar(const PlyElement& element, std::string_view name) {
  for (size_t p = 0; p < element.properties.size(); ++p)
    if (element.properties[p].name == name && !element.properties[p].list) return int(p);
  return -1;
}

void read_vertices(PlyBody& body, const PlyElement& element, std::vector<Vec3>& positions) {
  const int axis[3] = {find_scalar(element, "x"), find_scalar(element, "y"),
                       find_scalar(element, "z")};
  static const char* const kAxes[3] = {"x", "y", "z"};
  positions.reserve(element.count);
  for (uint64_t v = 0; v < element.count; ++v) {
    Vec3 p = Vec3::Zero();
    for (size_t q = 0; q < element.properties.size(); ++q) {
      const PlyProperty& property = element.properties[q];
      if (property.list) {
        skip_list(body, property);
        continue;
      }
      const double value = body.number(property.type);
      for (int a = 0; a < 3; ++a)
        if (axis[a] == int(q)) {
          try {
            check_mesh_coordinate(value, kAxes[a], body.where());
          } catch (const InputError& error) {
            throw PlyCoordinateError(error);
          }
          p[a] = value;
        }
    }
    positions.push_back(p);
  }
}

bool is_index_list(const PlyProperty& p) {
  return p.list && (p.name == "vertex_indices" || p.name == "vertex_index");
}

void read_faces(PlyBody& body, const PlyElement& element, uint64_t vertex_count,
                std::vector<Triangle>& triangles) {
  std::vector<uint32_t> polygon;
  for (uint64_t f = 0; f < element.count; ++f) {
    for (const PlyProperty& property : element.properties) {
      if (!is_index_list(property)) {
        if (property.list)
          skip_list(body, property);
        else
          (void)body.number(property.type);
        continue;
      }
      const uint64_t corners = body.whole(property.count_type, "a face's corner count");
      if (!body.ascii() && corners > body.remaining() / type_size(property.type))
        body.fail("a face of " + std::to_string(corners) +
                  " corners runs past the end of the file");
      polygon.clear();
      for (uint64_t k = 0; k < corners; ++k) {
        const uint64_t index = body.whole(property.type, "a vertex index");
        if (index >= vertex_count)
          body.fail("vertex index " + std::to_string(index) + " out of range (" +
                    std::to_string(vertex_count) + " vertices)");
        polygon.push_back(uint32_t(index));
      }
      if (corners < 3)
        body.fail("face " + std::to_string(f) + " has " + std::to_string(corners) +
                  " corners; a face needs at least 3");
      append_fan(polygon, triangles);
    }
  }
}

/// The vertex element (with x, y and z) and the face element's vertex_indices, checked.
void check_mesh_elements(const PlyHeader& header, const std::string& source) {
  const PlyElement* vertex = nullptr;
  const PlyElement* face = nullptr;
  // A second vertex or face element would be read as more of the first, against counts
  // checked for one.
  const auto first = [&](const PlyElement*& seen, const PlyElement& element) {
    if (seen != nullptr)
      throw InputError(at_line(source, element.line),
                       "a second '" + element.name + "' element (the first is on line " +
                           std::to_string(seen->line) + ")");
    seen = &element;
  };
  for (const PlyElement& element : header.elements) {
    if (element.name == "vertex") first(vertex, element);
    if (element.name == "face") first(face, element);
  }
  if (vertex == nullptr) throw InputError(source, "has no 'vertex' element");
  for (const char* axis : {"x", "y", "z"})
    if (find_scalar(*vertex, axis) < 0)
      throw InputError(at_line(source, vertex->line),
                       std::string("the vertex element has no scalar property '") + axis + "'");
  if (vertex->count >= uint64_t(UINT32_MAX))
    throw InputError(at_line(source, vertex->line), "too many vertices for 32-bit indices");
  bool indexed = false;
  if (face != nullptr)
    for (const PlyProperty& p : face->properties) indexed |= is_index_list(p);
  if (!indexed)
    throw InputError(source, "has no faces (a 'face' element with a 'vertex_indices' list)");
}

MeshFile parse_ply(std::string_view bytes, const std::string& source, UnknownLines unknown) {
  const PlyHeader header = parse_header(bytes, source, unknown);
  check_mesh_elements(header, source);
  check_counts(header, bytes.size() - header.body, source);
  uint64_t vertex_count = 0;
  for (const PlyElement& element : header.elements)
    if (element.name == "vertex") vertex_count = element.count;
  MeshPart part;
  PlyBody body(bytes, header, source);
  for (const PlyElement& element : header.elements) {
    if (element.name == "vertex") {
      read_vertices(body, element, part.positions);
    } else if (element.name == "face") {
      read_faces(body, element, vertex_count, part.triangles);
    } else if (!element.properties.empty()) {
      for (uint64_t i = 0; i < element.count; ++i)
        for (const PlyProperty& property : element.properties) {
          if (property.list)
            skip_list(body, property);
          else
            (void)body.number(property.type);
        }
    }
  }
  if (part.triangles.empty()) throw InputError(source, "has no faces");
  MeshFile file;
  file.parts.push_back(std::move(part));
  return file;
}

}  // namespace

MeshFile parse_ply(std::string_view bytes, const std::string& source) {
  return parse_ply(bytes, source, UnknownLines::refuse);
}

void check_ply_file(const std::string& path) {
  std::ifstream probe(path, std::ios::binary);
  std::string line;
  if (!std::getline(probe, line) || (line != "ply" && line != "ply\r")) return;
  probe.close();
  const std::string bytes = read_mesh_bytes(path);
  std::string_view rest = bytes;
  bool ended = false;
  while (!ended && !rest.empty()) {
    const size_t end = std::min(rest.find('\n'), rest.size());
    const std::vector<std::string_view> w = split_words(rest.substr(0, end));
    ended = !w.empty() && w[0] == "end_header";
    rest.remove_prefix(std::min(end + 1, rest.size()));
  }
  // assimp's PLY reader spins without end on a header cut short (it waits for end_header).
  if (!ended)
    throw InputError(path, "the PLY header ends without an 'end_header' line (a truncated file?)");
  PlyHeader parsed;
  try {
    // Leniently: assimp reads headers with lines of other writers (Wuson.ply has 'Created
    // by ...') and files a few bytes short, and says itself what else is wrong.
    parsed = parse_header(bytes, path, UnknownLines::skip);
  } catch (const InputError&) {
    return;
  }
  for (const PlyElement& element : parsed.elements) check_has_properties(element, path);
  // assimp takes NaN and infinite coordinates as they are (a NaN vertex silently vanished from
  // a triangle): kinray's own reader checks every coordinate and refuses such a file, and leaves
  // the problems it is stricter about than assimp (unknown header lines, a short body) to it.
  try {
    (void)parse_ply(bytes, path, UnknownLines::skip);
  } catch (const PlyCoordinateError& error) {
    throw InputError(error.where(), error.message());
  } catch (const InputError&) {
  }
}

MeshFile read_ply(const std::string& path) {
  return parse_ply(read_mesh_bytes(path), path);
}

}  // namespace kinray
