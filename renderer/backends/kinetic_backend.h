#pragma once
// The kinetic backend: the kinetic grid of frusta (kinetic/grid/frustum_grid.h) over the scene's
// camera-space flightplans. The grid is built by scan conversion at the first frame time; each
// later frame processes the events up to its time and reads the front triangle of every pixel
// out. Nothing is rasterized or traced per frame. The ID and depth buffers are written exactly as
// the Embree backend writes them (object index, triangle index within the object, the double
// plane depth of the hit triangle along the pixel-centre ray, as a float), and the colour comes
// from the shared shade_frame, so frames agree with Embree's up to ties.
//
// BackendConfig: width, height, threads, sort (DepthSortKind), audit.
#include <memory>

#include "kinetic/grid/grid_input.h"
#include "renderer/backends/backend.h"

namespace kinray {

/// The kinetic grid's view of `scene` at `width` x `height`: its objects' camera-space flightplans
/// (spans into `scene`, which must outlive the result) and the pixel-centre rays.
[[nodiscard]] GridInput kinetic_grid_input(const CameraSpaceScene& scene, int width, int height);

/// Creates the kinetic backend for `scene` (which must outlive it). Throws OptionError for an
/// empty image. Frame times must not decrease between render calls.
[[nodiscard]] std::unique_ptr<Backend> make_kinetic_backend(const CameraSpaceScene& scene,
                                                            const BackendConfig& config);

}  // namespace kinray
