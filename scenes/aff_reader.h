#pragma once
// The tokens of one AFF file (BART's extension of Eric Haines' NFF): words separated by white
// space, '{' and '}' always tokens of their own, '#' or '%' starting a comment to the end of the
// line, CR LF line ends read like LF. Every token keeps its line, so that every problem the scene
// builder finds is reported as `file:line: problem` (one line, as InputError).
#include <cstddef>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace kinray {

/// Reads the tokens of one AFF file and hands them out in order, checking what it hands out.
class AffReader {
 public:
  /// Reads `file` whole. Throws InputError naming the file when it cannot be read.
  explicit AffReader(std::filesystem::path file);
  /// Tokenizes `text` as if it were the content of `file` (tests, and files already read).
  AffReader(std::filesystem::path file, std::string_view text);

  [[nodiscard]] const std::filesystem::path& file() const { return m_file; }
  [[nodiscard]] bool at_end() const { return m_next >= m_tokens.size(); }
  /// The next token without consuming it; empty at the end of the file.
  [[nodiscard]] std::string_view peek() const;
  /// The next token, which must exist; `what` names it in the error ("a texture name").
  std::string word(const char* what);
  /// The next token as a finite number.
  double number(const char* what);
  /// The next token as an integer in [minimum, maximum].
  int integer(const char* what, int minimum, int maximum);
  /// Three numbers.
  void numbers(double* out, int count, const char* what);
  /// Consumes `token`, which must come next.
  void expect(std::string_view token);
  /// "file:line" of the token last handed out (or of the next one before any was read).
  [[nodiscard]] std::string where() const;
  /// Throws InputError at where() with `problem`.
  [[noreturn]] void fail(const std::string& problem) const;

 private:
  struct Token {
    std::string text;
    int line = 0;
  };
  std::string next_token(const char* what);

  std::filesystem::path m_file;
  std::vector<Token> m_tokens;
  size_t m_next = 0;
};

}  // namespace kinray
