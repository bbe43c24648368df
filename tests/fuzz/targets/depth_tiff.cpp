// The depth buffer reader (renderer/output/image_io.h), which `kinray regress` runs on reference folders.
#include "renderer/output/image_io.h"
#include "tests/fuzz/fuzz_target.h"

KINRAY_FUZZ_TARGET(depth_tiff) {
  kinray::Frame frame;
  kinray::read_depth_tiff(kinray::fuzz::write_scratch_file("depth.tiff", bytes), frame);
}
