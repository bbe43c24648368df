// The libFuzzer entry of one harness: the build links exactly one target file with this one
// (tests/fuzz/CMakeLists.txt), so the registry holds that target alone.
#include <cstdio>
#include <cstdlib>

#include "tests/fuzz/fuzz_target.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const kinray::fuzz::Entry entry = [] {
    if (kinray::fuzz::targets().size() != 1) {
      std::fprintf(stderr, "kinray fuzz: expected one target, found %zu\n",
                   kinray::fuzz::targets().size());
      std::abort();
    }
    return kinray::fuzz::targets().front().entry;
  }();
  kinray::fuzz::run_target(entry, {data, size});
  return 0;
}
