#include "scenes/aff_reader.h"

#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>

#include "util/input_error.h"

namespace kinray {
namespace {

bool is_space(char c) {
  return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\f' || c == '\v';
}

std::string shown(std::string_view token) {
  std::string text = "'" + std::string(token.substr(0, 40)) + (token.size() > 40 ? "...'" : "'");
  return text;
}

}  // namespace

AffReader::AffReader(std::filesystem::path file) : m_file(std::move(file)) {
  std::ifstream in(m_file, std::ios::binary);
  std::error_code error;
  if (!in || std::filesystem::is_directory(m_file, error))
    throw InputError(m_file.string(), "cannot read the file");
  std::ostringstream content;
  content << in.rdbuf();
  *this = AffReader(m_file, content.str());
}

AffReader::AffReader(std::filesystem::path file, std::string_view text) : m_file(std::move(file)) {
  int line = 1;
  size_t i = 0;
  while (i < text.size()) {
    const char c = text[i];
    if (c == '\n') {
      ++line;
      ++i;
    } else if (is_space(c)) {
      ++i;
    } else if (c == '#' || c == '%') {
      while (i < text.size() && text[i] != '\n') ++i;
    } else if (c == '{' || c == '}') {
      m_tokens.push_back({std::string(1, c), line});
      ++i;
    } else {
      const size_t start = i;
      while (i < text.size() && !is_space(text[i]) && text[i] != '{' && text[i] != '}') ++i;
      m_tokens.push_back({std::string(text.substr(start, i - start)), line});
    }
  }
}

std::string_view AffReader::peek() const {
  return at_end() ? std::string_view() : std::string_view(m_tokens[m_next].text);
}

std::string AffReader::next_token(const char* what) {
  if (at_end()) {
    m_next = m_tokens.size() + 1;  // where() reports the end of the file
    fail(std::string("expected ") + what + ", got the end of the file");
  }
  return m_tokens[m_next++].text;
}

std::string AffReader::word(const char* what) {
  return next_token(what);
}

double AffReader::number(const char* what) {
  const std::string token = next_token(what);
  double value = 0;
  const char* begin = token.data() + (token.size() > 1 && token[0] == '+' ? 1 : 0);
  const auto [end, error] = std::from_chars(begin, token.data() + token.size(), value);
  if (error != std::errc() || end != token.data() + token.size())
    fail(std::string("expected ") + what + " (a number), got " + shown(token));
  if (!std::isfinite(value)) fail(std::string(what) + " must be finite, got " + shown(token));
  return value;
}

int AffReader::integer(const char* what, int minimum, int maximum) {
  const std::string token = next_token(what);
  long long value = 0;
  const auto [end, error] = std::from_chars(token.data(), token.data() + token.size(), value);
  if (error != std::errc() || end != token.data() + token.size())
    fail(std::string("expected ") + what + " (an integer), got " + shown(token));
  if (value < minimum || value > maximum)
    fail(std::string(what) + " must lie in " + std::to_string(minimum) + ".." +
         std::to_string(maximum) + ", got " + token);
  return int(value);
}

void AffReader::numbers(double* out, int count, const char* what) {
  for (int i = 0; i < count; ++i) out[i] = number(what);
}

void AffReader::expect(std::string_view token) {
  const std::string got = next_token(("'" + std::string(token) + "'").c_str());
  if (got != token) fail("expected '" + std::string(token) + "', got " + shown(got));
}

std::string AffReader::where() const {
  int line = 0;
  if (m_tokens.empty())
    line = 1;
  else if (m_next == 0)
    line = m_tokens.front().line;
  else if (m_next <= m_tokens.size())
    line = m_tokens[m_next - 1].line;
  else
    line = m_tokens.back().line;
  return m_file.string() + ":" + std::to_string(line);
}

void AffReader::fail(const std::string& problem) const {
  throw InputError(where(), problem);
}

}  // namespace kinray
