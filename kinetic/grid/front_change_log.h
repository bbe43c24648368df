#pragma once
// The seam between the kinetic grid and exact motion blur (docs/design.md, "Exact motion blur"):
// while a log is attached, a band appends every change of a pixel's front triangle, with the time
// of the event that made it. Between two entries of a pixel its front is fixed, so the entries of a
// shutter window split each pixel's window into intervals with one front each. A band appends in
// event (time) order and owns its log, so bands log in parallel without locks.
#include <cstdint>
#include <vector>

namespace kinray {

/// One change of a pixel's front: from `time` on, the pixel's front is `front`.
struct FrontChange {
  double time = 0;
  uint32_t pixel = 0;  ///< row-major index in the whole image
  uint32_t front = 0;  ///< global triangle id (GridScene numbering), ~0u for none
};

/// A band's front changes in time order.
struct FrontChangeLog {
  std::vector<FrontChange> changes;
  void record(uint32_t pixel, double time, uint32_t front) {
    changes.push_back({time, pixel, front});
  }
};

}  // namespace kinray
