// The ID buffer reader (renderer/output/image_io.h), which `kinray regress` runs on reference folders.
#include "renderer/output/image_io.h"
#include "tests/fuzz/fuzz_target.h"

KINRAY_FUZZ_TARGET(id_png) {
  kinray::Frame frame;
  kinray::read_id_png(kinray::fuzz::write_scratch_file("id.png", bytes), frame);
}
