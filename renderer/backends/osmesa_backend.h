#pragma once
// The OSMesa reference backend ("osmesa"): the RasterBackend of id_rasterizer.h driven by an
// OSMesa (Mesa llvmpipe, software) context. OSMesa was removed from Mesa 25.1; everything
// OSMesa-specific is in osmesa_*.{h,cpp}, which the CMake option KINRAY_WITH_OSMESA leaves out.
//
// The context is created on the thread that calls make_osmesa_backend and reused for every frame;
// an OSMesa context is current on one thread at a time, so one backend must not render from two
// threads at once (render() makes it current on the calling thread). llvmpipe chooses its own
// rasterizer threads (LP_NUM_THREADS), so BackendConfig::threads does not apply.
#include <memory>

#include "renderer/backends/backend.h"
#include "renderer/backends/id_rasterizer.h"

namespace kinray {

/// Creates the OSMesa backend for `scene` (which must outlive it). Throws InputError when no
/// OSMesa context with a float depth buffer and clip control can be created, or the image is
/// larger than OSMesa's renderbuffers.
[[nodiscard]] std::unique_ptr<Backend> make_osmesa_backend(const CameraSpaceScene& scene,
                                                           const BackendConfig& config);

/// The OSMesa IdRasterizer alone, with its context created on the calling thread (for tests and
/// for other RasterBackend users). Throws as make_osmesa_backend.
[[nodiscard]] std::unique_ptr<IdRasterizer> make_osmesa_rasterizer();

}  // namespace kinray
