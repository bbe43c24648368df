// The JSON scene file parser (scenes/scene_file.h) on arbitrary text. Relative model and texture
// paths resolve into the empty scratch folder.
#include "scenes/scene_file.h"

#include "tests/fuzz/fuzz_target.h"

KINRAY_FUZZ_TARGET(scene_file) {
  const std::string text(bytes.begin(), bytes.end());
  (void)kinray::parse_scene_file(text, kinray::fuzz::scratch_folder() + "/scene.json");
}
