#include <gtest/gtest.h>

#include "kinetic/sort/depth_sort_kind.h"
#include "util/enum_names.h"

namespace kinray {
namespace {

TEST(EnumNames, DepthSortNamesRoundTripAndRejectOthers) {
  for (const auto& [kind, name] : kDepthSortNames) {
    EXPECT_STREQ(depth_sort_name(kind), name);
    EXPECT_EQ(find_enum(kDepthSortNames, name), kind);
  }
  EXPECT_EQ(enum_names(kDepthSortNames), "list, tournament, heap");
  EXPECT_EQ(enum_names(kDepthSortNames, "|"), "list|tournament|heap");
  EXPECT_FALSE(find_enum(kDepthSortNames, "bubble").has_value());
  EXPECT_FALSE(find_enum(kDepthSortNames, "List").has_value());
  EXPECT_FALSE(find_enum(kDepthSortNames, "").has_value());
}

}  // namespace
}  // namespace kinray
