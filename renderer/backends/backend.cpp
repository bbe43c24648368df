#include "renderer/backends/backend.h"

#include "renderer/antialiasing/pixel_samples.h"
#include "renderer/backends/auto_backend.h"
#include "renderer/backends/embree_backend.h"
#include "renderer/backends/kinetic_backend.h"
#ifdef KINRAY_WITH_OSMESA
#include "renderer/backends/osmesa_backend.h"
#endif
#include "util/input_error.h"

namespace kinray {
namespace {

using BackendFactory = std::unique_ptr<Backend> (*)(const CameraSpaceScene&, const BackendConfig&);

struct BackendEntry {
  const char* name;
  BackendFactory make;
};

// One line per backend; each factory validates its own part of the config.
const BackendEntry kBackends[] = {
    {"kinetic", &make_kinetic_backend},
    {"embree", &make_embree_backend},
    {"auto", &make_auto_backend},
#ifdef KINRAY_WITH_OSMESA
    {"osmesa", &make_osmesa_backend},
#endif
};

}  // namespace

void Backend::render_shutter(const ShutterWindow&, Frame&) {
  throw OptionError("shutter", "the " + name() + " backend has no motion blur");
}

void Backend::render_antialiased(double, Frame&) {
  throw OptionError("aa", "the " + name() + " backend has no exact antialiasing");
}

void Backend::render_supersampled(double, Frame&) {
  throw OptionError("aa_samples", "the " + name() + " backend does not supersample");
}

std::unique_ptr<Backend> make_backend(const std::string& name, const CameraSpaceScene& scene,
                                      const BackendConfig& config) {
  check_aa_samples(config.aa_samples);
  std::string names;
  for (const BackendEntry& entry : kBackends) {
    if (name != entry.name) {
      names += (names.empty() ? "" : ", ") + std::string(entry.name);
      continue;
    }
    std::unique_ptr<Backend> backend = entry.make(scene, config);
    if (config.shutter.enabled() && !backend->has_motion_blur())
      throw OptionError("shutter", "the " + name + " backend has no motion blur (kinetic and embree have)");
    if (config.aa == Antialiasing::exact && !backend->has_exact_antialiasing())
      throw OptionError("aa", "the " + name +
                                  " backend has no exact antialiasing (kinetic has; the sampling "
                                  "backends take --aa-samples)");
    if (config.aa_samples > 1 && !backend->has_supersampling())
      throw OptionError("aa_samples",
                        "the " + name + " backend does not supersample (embree does)");
    return backend;
  }
  throw OptionError("backend", "unknown backend '" + name + "' (available: " + names + ")");
}

}  // namespace kinray
