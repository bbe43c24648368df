// The PLY reader of mesh sequences (scenes/ply_reader.h) on arbitrary bytes: ascii and binary
// bodies, any header.
#include <string_view>

#include "scenes/ply_reader.h"
#include "tests/fuzz/fuzz_target.h"

KINRAY_FUZZ_TARGET(ply_reader) {
  const std::string_view text(reinterpret_cast<const char*>(bytes.data()), bytes.size());
  (void)kinray::parse_ply(text, "fuzz.ply");
}
