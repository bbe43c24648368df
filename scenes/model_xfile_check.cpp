#include "scenes/model_xfile_check.h"

#include <cctype>
#include <charconv>
#include <fstream>
#include <optional>
#include <sstream>
#include <vector>

#include "util/input_error.h"

namespace kinray {

namespace {

/// One block of the file being read: its template ("Mesh", "SkinWeights", ...) and the plain
/// values met directly inside it so far.
struct Block {
  std::string type;
  std::string name;
  bool is_template = false;
  std::vector<std::string> values;
  unsigned long long vertex_count = 0;  // Mesh: its first value
  bool counted = false;
};

bool parse_count(const std::string& token, unsigned long long& out) {
  const auto [end, error] = std::from_chars(token.data(), token.data() + token.size(), out);
  return error == std::errc() && end == token.data() + token.size();
}

/// The text of a text-format X file after its 16-byte header; nullopt for any other file.
std::optional<std::string> read_text_x_file(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  if (!file) return std::nullopt;  // assimp reports unreadable files
  char header[16] = {};
  file.read(header, sizeof header);
  if (file.gcount() < 16 || std::string(header, 4) != "xof " ||
      std::string(header + 8, 4) != "txt ")
    return std::nullopt;
  std::ostringstream buffer;
  buffer << file.rdbuf();
  return buffer.str();
}

/// Gives the tokens since the last delimiter to the innermost block; a mesh's first value must
/// be its vertex count.
void flush_values(const std::string& path, std::vector<Block>& stack,
                  std::vector<std::string>& pending) {
  Block& block = stack.back();
  for (std::string& token : pending) {
    if (block.type == "Mesh" && !block.is_template && !block.counted) {
      if (!parse_count(token, block.vertex_count))
        throw InputError(path, "mesh '" + block.name + "' does not start with a vertex count");
      block.counted = true;
    }
    block.values.push_back(std::move(token));
  }
  pending.clear();
}

/// A SkinWeights block must weigh only vertices of the innermost mesh around it.
void check_skin(const std::string& path, const std::vector<Block>& stack, const Block& skin) {
  const Block* mesh = nullptr;
  for (auto it = stack.rbegin(); it != stack.rend(); ++it)
    if (it->type == "Mesh" && !it->is_template) {
      mesh = &*it;
      break;
    }
  if (mesh == nullptr) return;  // assimp ignores weights outside a mesh
  unsigned long long count = 0;
  const std::string bone = skin.values.empty() ? "" : skin.values[0];
  if (skin.values.size() < 2 || !parse_count(skin.values[1], count) ||
      skin.values.size() < 2 + count)
    throw InputError(path, "SkinWeights of bone " + bone + " in mesh '" + mesh->name +
                               "' has an unreadable weight count");
  for (unsigned long long i = 0; i < count; ++i) {
    unsigned long long vertex = 0;
    if (!parse_count(skin.values[2 + i], vertex))
      throw InputError(path, "SkinWeights of bone " + bone + " in mesh '" + mesh->name +
                                 "' has an unreadable vertex index '" + skin.values[2 + i] + "'");
    if (vertex >= mesh->vertex_count)
      throw InputError(path, "SkinWeights of bone " + bone + " in mesh '" + mesh->name +
                                 "' weighs vertex " + std::to_string(vertex) +
                                 ", but the mesh has " + std::to_string(mesh->vertex_count) +
                                 " vertices");
  }
}

/// Opens a block at '{', typed and named by the pending tokens: [template] type [name].
void open_block(std::vector<Block>& stack, std::vector<std::string>& pending) {
  Block block;
  if (!pending.empty() && pending[0] == "template") {
    block.is_template = true;
    pending.erase(pending.begin());
  }
  if (!pending.empty()) block.type = pending[0];
  if (pending.size() > 1) block.name = pending[1];
  pending.clear();
  // A template's body declares members; it holds no data to check.
  if (stack.back().is_template) block.is_template = true;
  stack.push_back(std::move(block));
}

}  // namespace

void check_x_skin_weights(const std::string& path) {
  const std::optional<std::string> contents = read_text_x_file(path);
  if (!contents) return;
  const std::string& text = *contents;

  std::vector<Block> stack = {Block{}};
  std::vector<std::string> pending;  // tokens since the last delimiter
  for (size_t i = 16; i < text.size();) {
    const char c = text[i];
    if (std::isspace(static_cast<unsigned char>(c))) {
      ++i;
    } else if (c == '#' || (c == '/' && i + 1 < text.size() && text[i + 1] == '/')) {
      while (i < text.size() && text[i] != '\n') ++i;
    } else if (c == ',' || c == ';') {
      flush_values(path, stack, pending);
      ++i;
    } else if (c == '{') {
      open_block(stack, pending);
      ++i;
    } else if (c == '}') {
      flush_values(path, stack, pending);
      if (stack.size() > 1) {
        if (stack.back().type == "SkinWeights" && !stack.back().is_template)
          check_skin(path, stack, stack.back());
        stack.pop_back();
      }
      ++i;
    } else if (c == '"') {
      const size_t end = text.find('"', i + 1);
      const size_t stop = end == std::string::npos ? text.size() : end + 1;
      pending.push_back(text.substr(i, stop - i));
      i = stop;
    } else {
      size_t end = i;
      while (end < text.size() && !std::isspace(static_cast<unsigned char>(text[end])) &&
             std::string_view(",;{}\"").find(text[end]) == std::string_view::npos)
        ++end;
      pending.push_back(text.substr(i, end - i));
      i = end;
    }
  }
}

}  // namespace kinray
