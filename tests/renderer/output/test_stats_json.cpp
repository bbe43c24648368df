// Counters declared once (kinetic/core/counters.h): every declared counter is summed and reaches
// the
// --stats JSON under its key, and the quality measures are the same function for every structure.
#include <gtest/gtest.h>

#include "kinetic/collision/ksl_stats.h"
#include "kinetic/grid/grid_stats.h"
#include "kinetic/sort/kinetic_sort.h"
#include "kinetic/tree/tree_stats.h"
#include "renderer/output/stats_json.h"

namespace kinray {
namespace {

TEST(StatsJson, EveryGridCounterIsSummedAndWrittenUnderItsKey) {
  GridStats band;
  band.events.boundary = 5;
  band.events.remove = 2;
  band.records_born = 7;
  band.pixel_memory_bytes = 1000;
  GridStats total;
  total += band;
  total += band;
  EXPECT_EQ(total.events.total(), 14u);
  const nlohmann::json events = event_counts_json(total.events);
  EXPECT_EQ(events["boundary"], 10);
  EXPECT_EQ(events["delete"], 4);  // the member is `remove`; users read "delete"
  EXPECT_EQ(events["total"], 14);
  EXPECT_EQ(events.size(), 8u);  // seven kinds and the total
  const nlohmann::json counters = counters_json(total);
  EXPECT_EQ(counters["records_born"], 14);
  EXPECT_EQ(counters["pixel_memory_bytes"], 2000);
  EXPECT_EQ(counters["certificates_live_max"], 0);
  EXPECT_EQ(counters.size(), 22u);
}

TEST(StatsJson, EventKindsOfEveryStructureHaveTheirKeysAndTotal) {
  KslEventCounts ksl;
  ksl.overlap = 3;
  ksl.witness_change = 4;
  ksl += ksl;
  EXPECT_EQ(event_counts_json(ksl)["witness_change"], 8);
  EXPECT_EQ(ksl.total(), 14u);
  EXPECT_EQ(ksl.external(), 6u);
  TreeEventCounts tree;
  tree.leaf = 1;
  tree.remove = 2;
  EXPECT_EQ(event_counts_json(tree)["delete"], 2);
  EXPECT_EQ(event_counts_json(tree)["total"], 3);
  KineticSortStats sort;
  sort.work = 9;
  sort += sort;
  EXPECT_EQ(counters_json(sort)["work"], 18);
}

TEST(StatsJson, QualityMeasuresAreDesignsDefinitions) {
  QualityCounts counts;
  counts.certificates_live_max = 50;
  counts.certificates_live = 40;
  counts.certificates_computed = 300;
  counts.events = 100;
  counts.events_internal = 75;
  counts.events_external = 25;
  counts.objects_present = 20;
  const nlohmann::json q = quality_json(counts);
  EXPECT_EQ(q["compactness"], 50);          // live certificates, at most
  EXPECT_DOUBLE_EQ(q["responsiveness"], 3.0);  // computed per event
  EXPECT_DOUBLE_EQ(q["locality"], 2.0);        // live per object
  EXPECT_DOUBLE_EQ(q["efficiency"], 3.0);      // internal per external
  KineticSortStats sort;
  sort.certificates_live = 12;
  sort.work = 30;
  sort.events_internal = 4;
  sort.events_external = 2;
  const QualityMeasures m = quality_measures(quality_counts(sort, 6));
  EXPECT_EQ(m.compactness, 12u);
  EXPECT_DOUBLE_EQ(m.locality, 2.0);
  EXPECT_DOUBLE_EQ(m.responsiveness, 5.0);
  EXPECT_DOUBLE_EQ(m.efficiency, 2.0);
}

}  // namespace
}  // namespace kinray
