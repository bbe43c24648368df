#pragma once
// What the kinetic grid of frusta consumes: the pixel-centre rays of the image (util/pixel_rays.h)
// and the triangle meshes as camera-space flightplans (kinetic/motion/flightplan_mesh.h).
#include <vector>

#include "kinetic/motion/flightplan_mesh.h"
#include "util/pixel_rays.h"

namespace kinray {

/// The grid's whole input.
struct GridInput {
  PixelRays rays;
  std::vector<FlightplanMesh> meshes;
};

}  // namespace kinray
