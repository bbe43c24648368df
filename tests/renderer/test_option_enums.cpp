// Each option value is spelled once, in its enum's table: the tables name every value, no name
// twice, and the spellings the JSON and the command line have always used.
#include <gtest/gtest.h>

#include <set>
#include <string>

#include "renderer/backends/embree_build.h"
#include "renderer/shadows/shadow_tracer.h"

namespace kinray {
namespace {

template <class Enum, size_t N>
void expect_round_trip(const std::array<EnumName<Enum>, N>& table) {
  std::set<std::string> names;
  std::set<Enum> values;
  for (const auto& [value, name] : table) {
    EXPECT_TRUE(names.insert(name).second) << name << " twice";
    EXPECT_TRUE(values.insert(value).second) << name << ": its value twice";
    EXPECT_STREQ(enum_name(table, value), name);
    EXPECT_EQ(find_enum(table, name), value) << name;
  }
}

TEST(OptionEnums, EmbreeBuildNames) {
  expect_round_trip(kEmbreeBuildNames);
  EXPECT_STREQ(embree_build_name(EmbreeBuild::kRefit), "refit");
  EXPECT_STREQ(embree_build_name(EmbreeBuild::kRebuild), "rebuild");
  EXPECT_FALSE(find_enum(kEmbreeBuildNames, "fast").has_value());
}

TEST(OptionEnums, ShadowTreeNames) {
  expect_round_trip(kShadowTreeNames);
  EXPECT_EQ(enum_names(kShadowTreeNames), "aabb, boxtree, refit, brute");
  EXPECT_FALSE(find_enum(kShadowTreeNames, "octree").has_value());
}

TEST(OptionEnums, PacketWidths) {
  for (int packet : {1, 4, 8, 16}) EXPECT_TRUE(is_embree_packet_width(packet)) << packet;
  for (int packet : {0, 2, 3, 32, -4}) EXPECT_FALSE(is_embree_packet_width(packet)) << packet;
}

}  // namespace
}  // namespace kinray
