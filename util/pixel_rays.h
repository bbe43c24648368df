#pragma once
// The pixel-centre rays of an image, shared by the kinetic grid, the references (Embree, OSMesa)
// and the scene's camera space (scenes/camera_space.h), so that all of them trace bit-identical
// rays: d_ij = (x(i), y(j), 1) in camera space, eye at the origin.
#include <cstddef>

#include <Eigen/Core>

namespace kinray {

/// Pixel-centre ray directions of a W x H image: d_ij = (x(i), y(j), 1), row 0 at the top.
struct PixelRays {
  int width = 0, height = 0;
  [[nodiscard]] double x(int i) const {
    return ((2.0 * i + 1.0) / width - 1.0) * (double(width) / double(height));
  }
  [[nodiscard]] double y(int j) const { return 1.0 - (2.0 * j + 1.0) / height; }
  [[nodiscard]] Eigen::Vector3d direction(int i, int j) const { return {x(i), y(j), 1.0}; }
  [[nodiscard]] size_t pixel_count() const { return size_t(width) * size_t(height); }
};

}  // namespace kinray
