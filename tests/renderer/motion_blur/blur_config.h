#pragma once
// The backend configuration of the motion blur tests: S = 0.5, two threads, `samples` time samples
// for the sampling backends, the kinetic structures audited unless `audit` is false; and the
// comparison the tests make of a blurred frame with a reference of many samples.
#include "renderer/backends/backend.h"
#include "renderer/motion_blur/shutter.h"
#include "scenes/camera_space.h"
#include "verification/image_diff.h"

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

/// One window blurred by the kinetic backend (audited) and by Embree at `samples`, each compared
/// with Embree at 1024 samples: their errors, and the kinetic frame.
struct BlurErrors {
  ColorError kinetic, sampled;
  Frame kinetic_frame;
};
inline BlurErrors blur_errors(const CameraSpaceScene& cs, const ShutterWindow& window, int size,
                              int samples) {
  auto kinetic = make_backend("kinetic", cs, blur_config(size, size));
  auto reference = make_backend("embree", cs, blur_config(size, size, 1024, false));
  auto sampled = make_backend("embree", cs, blur_config(size, size, samples, false));
  BlurErrors out;
  Frame r, s;
  kinetic->render_shutter(window, out.kinetic_frame);
  reference->render_shutter(window, r);
  sampled->render_shutter(window, s);
  out.kinetic = compare_colors(out.kinetic_frame, r);
  out.sampled = compare_colors(s, r);
  return out;
}

}  // namespace kinray::test
