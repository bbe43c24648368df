#pragma once
// The backend configuration of the motion blur tests: S = 0.5, two threads, `samples` time samples
// for the sampling backends, the kinetic structures audited unless `audit` is false.
#include "renderer/backends/backend.h"

namespace kinray::test {

inline BackendConfig blur_config(int width, int height, int samples = 16, bool audit = true) {
  BackendConfig c;
  c.width = width;
  c.height = height;
  c.threads = 2;
  c.audit = audit;
  c.shutter.shutter = 0.5;
  c.shutter.samples = samples;
  return c;
}

}  // namespace kinray::test
