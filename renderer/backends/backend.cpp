#include "renderer/backends/backend.h"

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

std::unique_ptr<Backend> make_backend(const std::string& name, const CameraSpaceScene& scene,
                                      const BackendConfig& config) {
  std::string names;
  for (const BackendEntry& entry : kBackends) {
    if (name != entry.name) {
      names += (names.empty() ? "" : ", ") + std::string(entry.name);
      continue;
    }
    std::unique_ptr<Backend> backend = entry.make(scene, config);
    if (config.shutter.enabled() && !backend->has_motion_blur())
      throw OptionError("shutter", "the " + name + " backend has no motion blur (kinetic and embree have)");
    return backend;
  }
  throw OptionError("backend", "unknown backend '" + name + "' (available: " + names + ")");
}

}  // namespace kinray
