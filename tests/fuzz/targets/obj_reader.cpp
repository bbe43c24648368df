// The OBJ reader of mesh sequences (scenes/obj_reader.h) on arbitrary bytes.
#include "scenes/obj_reader.h"

#include <string_view>

#include "tests/fuzz/fuzz_target.h"

KINRAY_FUZZ_TARGET(obj_reader) {
  const std::string_view text(reinterpret_cast<const char*>(bytes.data()), bytes.size());
  (void)kinray::parse_obj(text, "fuzz.obj");
}
