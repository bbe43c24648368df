// The BART scene reader (scenes/aff_parser.h, aff_scene.h) on arbitrary text: the parser with its
// includes (resolved in the empty scratch folder), then the scene built from the document.
//
// A document whose animation asks for more than 64 frames is parsed but not built: building
// samples every mesh at every frame (up to a million, a valid request for a big scene), which
// would only report the fuzzer's own time and memory limits.
#include "scenes/aff_scene.h"

#include "scenes/aff_parser.h"
#include "tests/fuzz/fuzz_target.h"

KINRAY_FUZZ_TARGET(aff_scene) {
  const std::string path = kinray::fuzz::write_scratch_file("scene.aff", bytes);
  const kinray::AffDocument document = kinray::parse_aff(path);
  if (document.range && document.range->frames > 64) return;
  (void)kinray::build_aff_scene(document, path);
}
