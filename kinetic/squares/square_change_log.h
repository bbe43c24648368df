#pragma once
// The seam between the per-square sets and antialiasing under a shutter (docs/design.md, "Exact
// antialiasing": areas move continuously between the events of the pixel, integrated in time
// between them): while logging is on, every triangle that enters or leaves a pixel's set is
// appended with the time of the event that moved it, in event order. Between two entries of a
// pixel its set is fixed.
#include <cstdint>
#include <vector>

namespace kinray {

/// One member of a pixel's set.
struct SquareTriangle {
  uint32_t mesh = 0;      ///< index into GridInput::meshes
  uint32_t triangle = 0;  ///< index into that mesh's triangles
  friend bool operator==(const SquareTriangle&, const SquareTriangle&) = default;
};

/// From `time` on, `triangle` is in (entered) or out of (left) the set of `pixel`.
struct SquareChange {
  double time = 0;
  uint32_t pixel = 0;  ///< row-major, row 0 at the top
  SquareTriangle triangle;
  bool entered = false;
};

using SquareChangeLog = std::vector<SquareChange>;

}  // namespace kinray
