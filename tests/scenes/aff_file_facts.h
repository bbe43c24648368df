#pragma once
// What a BART scene's files say about it, read straight from their words for the tests to check
// the loader against: the triangles of every mesh over every included file, the animation range
// (`a start end frames`) and the view's resolution. A walk over whitespace-separated words with
// comments cut, independent of kinray's AFF reader.
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace kinray::test {

/// The words of an AFF file, '#' comments removed.
inline std::vector<std::string> aff_words(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::vector<std::string> words;
  for (std::string line; std::getline(in, line);) {
    std::istringstream text(line.substr(0, line.find('#')));
    for (std::string word; text >> word;) words.push_back(word);
  }
  return words;
}

/// The sum of the `triangles N` counts of `file` and of every file it includes (`i DETAIL
/// FILE`, relative to the including file's folder), each inclusion counted.
inline size_t aff_triangle_count(const std::filesystem::path& file) {
  const std::vector<std::string> words = aff_words(file);
  size_t triangles = 0;
  for (size_t k = 0; k + 1 < words.size(); ++k) {
    if (words[k] == "triangles") triangles += std::stoul(words[k + 1]);
    if (words[k] == "i" && k + 2 < words.size())
      triangles += aff_triangle_count(file.parent_path() / words[k + 2]);
  }
  return triangles;
}

/// The number after the first occurrence of `keyword`, and the `count` numbers after it.
inline std::vector<double> aff_numbers_after(const std::filesystem::path& file,
                                             const std::string& keyword, size_t count) {
  const std::vector<std::string> words = aff_words(file);
  for (size_t k = 0; k + count < words.size(); ++k)
    if (words[k] == keyword) {
      std::vector<double> numbers;
      for (size_t n = 1; n <= count; ++n) numbers.push_back(std::stod(words[k + n]));
      return numbers;
    }
  return {};
}

}  // namespace kinray::test
