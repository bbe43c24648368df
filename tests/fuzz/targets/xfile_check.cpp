// The DirectX skin-weight check that runs before assimp sees a .x file
// (scenes/model_xfile_check.h).
#include "scenes/model_xfile_check.h"
#include "tests/fuzz/fuzz_target.h"

KINRAY_FUZZ_TARGET(xfile_check) {
  kinray::check_x_skin_weights(kinray::fuzz::write_scratch_file("model.x", bytes));
}
