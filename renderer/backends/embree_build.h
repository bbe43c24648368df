#pragma once
// How the Embree backend keeps its BVH across frames (BackendConfig::embree_build, --embree-mode),
// and the ray packet widths it traces (--packet): each spelled once, here.
#include <array>

#include "util/enum_names.h"

namespace kinray {

enum class EmbreeBuild {
  kRebuild,  ///< a new scene each frame, built from scratch
  kRefit,    ///< one persistent scene, its BVH refitted each frame
};

/// The one spelling of each build mode: command line, help, JSON ("mode": "refit"), bench names.
inline constexpr std::array kEmbreeBuildNames{
    EnumName{EmbreeBuild::kRebuild, "rebuild"},
    EnumName{EmbreeBuild::kRefit, "refit"},
};

[[nodiscard]] constexpr const char* embree_build_name(EmbreeBuild build) {
  return enum_name(kEmbreeBuildNames, build);
}

/// Ray packet widths the backend knows: 1 (rtcIntersect1) and rtcIntersect4/8/16. Which of them
/// this machine traces natively is embree_packet_widths() (renderer/backends/embree_backend.h).
inline constexpr std::array kEmbreePacketWidths{1, 4, 8, 16};

[[nodiscard]] constexpr bool is_embree_packet_width(int packet) {
  for (int width : kEmbreePacketWidths)
    if (width == packet) return true;
  return false;
}

}  // namespace kinray
