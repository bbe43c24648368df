// The whole model import path (scenes/model_import.h), guards included: the .x check, the reading
// child of model_guard.h, assimp's own reading and the conversion into a validated scene. assimp
// picks its loader by the file's extension first, so the first byte chooses the extension
// and the rest is the file.
#include "scenes/model_import.h"

#include <array>

#include "tests/fuzz/fuzz_target.h"

namespace {

// The formats of animated models kinray is used with (README "Scenes"), and a few static ones.
constexpr std::array<const char*, 16> kExtensions = {"glb", "gltf", "fbx", "dae", "x",   "md5mesh",
                                                     "bvh", "obj",  "ply", "stl", "smd", "ms3d",
                                                     "b3d", "3ds",  "md2", "off"};

}  // namespace

KINRAY_FUZZ_TARGET(model_import) {
  if (bytes.empty()) return;
  const std::string name = std::string("model.") + kExtensions[bytes[0] % kExtensions.size()];
  kinray::ModelOptions options;
  options.import_timeout = 20;  // a hang is a finding, but libFuzzer's own -timeout reports it
  (void)kinray::load_model(kinray::fuzz::write_scratch_file(name, bytes.subspan(1)), options);
}
