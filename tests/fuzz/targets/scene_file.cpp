// The JSON scene file parser (scenes/scene_file.h) on arbitrary text. Relative model and texture
// paths resolve into the empty scratch folder.
//
// Texts with a number of 1000 or more (four digits before any decimal point, or an exponent of 3
// or more) are skipped: they are valid requests for big scenes (a sphere of 5e7 triangles, a key
// rate of 1e6), slow and memory-hungry by design rather than parser bugs, and would only report
// the fuzzer's own time and memory limits. Everything else about numbers (signs, fractions, tiny
// and negative exponents, NaN spellings) is still fuzzed.
#include <cctype>
#include <string_view>

#include "scenes/scene_file.h"
#include "tests/fuzz/fuzz_target.h"

namespace {

bool asks_for_a_big_scene(std::string_view text) {
  auto digit = [&](size_t i) { return i < text.size() && std::isdigit((unsigned char)text[i]); };
  for (size_t i = 0; i < text.size();) {
    if (!digit(i)) {
      ++i;
      continue;
    }
    const bool fraction = i > 0 && text[i - 1] == '.';
    size_t end = i;
    while (digit(end)) ++end;
    if (!fraction && end - i >= 4) return true;
    if (end < text.size() && (text[end] == 'e' || text[end] == 'E')) {
      size_t e = end + 1;
      if (e < text.size() && text[e] == '+') ++e;
      size_t exponent_end = e;
      while (digit(exponent_end)) ++exponent_end;
      if (exponent_end > e && (exponent_end - e > 1 || text[e] >= '3')) return true;
    }
    i = end;
  }
  return false;
}

}  // namespace

KINRAY_FUZZ_TARGET(scene_file) {
  const std::string text(bytes.begin(), bytes.end());
  if (asks_for_a_big_scene(text)) return;
  (void)kinray::parse_scene_file(text, kinray::fuzz::scratch_folder() + "/scene.json");
}
