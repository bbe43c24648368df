#pragma once
// The per-pixel kinetic depth order of the frustum grid (FrustumGridConfig::sort, --sort).
#include <array>

#include "util/enum_names.h"

namespace kinray {

enum class DepthSortKind { kList, kTournament, kHeap };

/// The one spelling of each depth sort: command line, help, --stats JSON ("sort": "list").
inline constexpr std::array kDepthSortNames{
    EnumName{DepthSortKind::kList, "list"},
    EnumName{DepthSortKind::kTournament, "tournament"},
    EnumName{DepthSortKind::kHeap, "heap"},
};

[[nodiscard]] constexpr const char* depth_sort_name(DepthSortKind kind) {
  return enum_name(kDepthSortNames, kind);
}

}  // namespace kinray
