// The PLY reader of mesh sequences (scenes/ply_reader.h) on arbitrary bytes: ascii and binary
// bodies, any header.
#include "scenes/ply_reader.h"

#include <string_view>

#include "tests/fuzz/fuzz_target.h"

KINRAY_FUZZ_TARGET(ply_reader) {
  const std::string_view text(reinterpret_cast<const char*>(bytes.data()), bytes.size());
  (void)kinray::parse_ply(text, "fuzz.ply");
}
