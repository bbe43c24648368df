#pragma once
// `--aa`: how a pixel's colour is filtered over its square. `none` shades the pixel-centre ray
// (every backend); `exact` is the box filter computed from the visible regions of the square
// (kinetic backend: the kinetic per-square sets, kinetic/squares/, read out by exact_pixel.h).
// The sampling peer is `--aa-samples N` (embree_supersampling.h).
#include <array>

#include "util/enum_names.h"

namespace kinray {

enum class Antialiasing { none, exact };

/// The one spelling of each mode: --aa, help, JSON.
inline constexpr std::array kAntialiasingNames{
    EnumName{Antialiasing::none, "none"},
    EnumName{Antialiasing::exact, "exact"},
};

[[nodiscard]] inline const char* antialiasing_name(Antialiasing mode) {
  return enum_name(kAntialiasingNames, mode);
}

}  // namespace kinray
