// kinray bench as a library: a tiny run must measure both sides, agree with Embree, and report
// consistent figures; the break-even point and the charts follow from the numbers.
#include <algorithm>
#include <filesystem>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

#include "renderer/backends/embree_backend.h"
#include "util/input_error.h"
#include "verification/benchmark.h"
#include "verification/chart.h"

namespace kinray {
namespace {

TEST(Benchmark, TinyRunMeasuresBothSidesAndAgrees) {
  BenchParams params;
  params.base.scene = "wavy-sphere:triangles=300";
  params.base.width = 48;
  params.base.height = 40;
  params.base.threads = 1;
  params.base.time = std::pair{0.0, 2.0 / 24.0};  // two keyframe intervals at 24 keys/s
  params.inbetweens = {1, 3};
  params.repetitions = 1;
  params.reference_frames = 3;
  params.embree_modes = {{EmbreeBuild::kRefit, 1}, {EmbreeBuild::kRebuild, embree_packet_widths().back()}};
  const BenchReport report = run_benchmark(params);
  ASSERT_EQ(report.points.size(), 2u);
  for (const BenchPoint& p : report.points) {
    EXPECT_EQ(p.sweep, "inbetweens");
    EXPECT_EQ(p.frames, size_t(p.inbetweens) * p.key_intervals + 1);
    EXPECT_EQ(p.key_intervals, 2u);
    EXPECT_GT(p.kinetic_ms_per_frame, 0);
    EXPECT_GT(p.kinetic_readout_ms, 0);
    // Both peers ran, measured frames and agree with the kinetic frames; the best is the fastest.
    ASSERT_EQ(p.embree.size(), 2u);
    EXPECT_EQ(p.mismatch_real, 0u);
    EXPECT_GT(p.pixels_compared, 0u);
    for (const BenchPoint::Peer& peer : p.embree) {
      EXPECT_GT(peer.frames_measured, 0u) << peer.mode;
      EXPECT_EQ(peer.mismatch_real, 0u) << peer.mode;
    }
    const auto fastest = std::min_element(
        p.embree.begin(), p.embree.end(),
        [](const auto& a, const auto& b) { return a.ms_per_frame < b.ms_per_frame; });
    EXPECT_EQ(p.embree_best_mode, fastest->mode);
    EXPECT_GT(p.speedup_vs_best_embree, 0);
    // The per-frame event counts add up to the interval's events whatever the frame count.
    uint64_t per_frame_sum = 0;
    for (const auto& n : p.kinetic_stats["kinetic"]["per_frame"]["events"]) per_frame_sum += n.get<uint64_t>();
    EXPECT_EQ(per_frame_sum, p.kinetic_stats["events"]["total"].get<uint64_t>());
  }
  // The events depend on the motion, not on the number of frames read out.
  EXPECT_EQ(report.points[0].kinetic_stats["events"], report.points[1].kinetic_stats["events"]);
  const nlohmann::json json = report.to_json();
  for (const char* key : {"kinetic_ms_per_frame", "embree_best_ms_per_frame", "embree_best_mode",
                          "speedup_vs_best_embree", "mismatch_real"})
    EXPECT_TRUE(json["points"][0].contains(key)) << key;
  EXPECT_NE(report.to_csv().find("kinetic"), std::string::npos);
  // One thread was measured: the cost per event is that point's events time over its events.
  const BenchPoint& first = report.points[0];
  ASSERT_TRUE(report.ns_per_event_one_thread);
  EXPECT_NEAR(*report.ns_per_event_one_thread,
              1e6 * first.kinetic_events_ms * double(first.frames) /
                  first.kinetic_stats["events"]["total"].get<double>(),
              1e-9);
  EXPECT_EQ(json["scene"], params.base.scene);
  EXPECT_DOUBLE_EQ(json["ns_per_event_one_thread"].get<double>(), *report.ns_per_event_one_thread);
  EXPECT_TRUE(json.contains("break_even_inbetweens"));
}

TEST(Benchmark, BreakEvenInterpolatesInLogK) {
  BenchReport report;
  auto point = [](int k, double kinetic, double embree) {
    BenchPoint p;
    p.sweep = "inbetweens";
    p.inbetweens = k;
    p.kinetic_ms_per_frame = kinetic;
    p.embree_best_ms_per_frame = embree;
    return p;
  };
  report.points = {point(1, 40, 10), point(4, 10, 10), point(16, 2, 10)};
  EXPECT_DOUBLE_EQ(*report.break_even_inbetweens(), 4.0);
  report.points = {point(2, 30, 10), point(8, 5, 10)};  // margins -20 and +5: 4/5 of the way
  EXPECT_NEAR(*report.break_even_inbetweens(), std::exp2(1 + 2 * 0.8), 1e-12);
  report.points = {point(1, 30, 10)};
  EXPECT_FALSE(report.break_even_inbetweens());
}

TEST(Benchmark, BadListsAreRejected) {
  EXPECT_THROW(parse_int_list("1,,4", "--inbetweens"), InputError);
  EXPECT_THROW(parse_int_list("0", "--inbetweens"), InputError);
  EXPECT_THROW(parse_int_list("2x", "--triangles"), InputError);
  EXPECT_THROW(parse_embree_modes("refit/3"), InputError);
  EXPECT_THROW(parse_embree_modes("fast/8"), InputError);
  EXPECT_EQ(parse_embree_modes("rebuild/8,refit").back().packet, 1);
  EXPECT_EQ(parse_embree_modes("rebuild/8,refit").front().name(), "rebuild/8");
  EXPECT_EQ(parse_embree_modes("rebuild/8,refit").back().build, EmbreeBuild::kRefit);
}

TEST(Chart, WritesAPngOfTheAskedSize) {
  Chart chart;
  chart.title = "test";
  chart.log_x = chart.log_y = true;
  chart.series = {{"a", {1, 10, 100}, {5, 2, 1}}, {"b", {1, 100}, {3, 3}, Color(1, 0, 0), true}};
  chart.marker_x = 10;
  const std::string path = (std::filesystem::path(testing::TempDir()) / "kinray_chart.png").string();
  write_chart_png(chart, path, 400, 300);
  const cv::Mat image = cv::imread(path);
  ASSERT_FALSE(image.empty());
  EXPECT_EQ(image.cols, 400);
  EXPECT_EQ(image.rows, 300);
  Chart empty;
  EXPECT_THROW(write_chart_png(empty, path), InputError);
}

}  // namespace
}  // namespace kinray

namespace kinray {
namespace {

// The default peers are those this machine's Embree can run (no 16-wide packets without
// AVX-512), and a peer it cannot run is refused before anything is measured.
TEST(Benchmark, DefaultPeersAreWhatTheMachineOffers) {
  const std::vector<int> widths = embree_packet_widths();
  const std::vector<EmbreeMode> modes = default_embree_modes();
  ASSERT_GE(modes.size(), 2u);
  EXPECT_EQ(modes.front().name(), "rebuild/1");
  for (const EmbreeMode& mode : modes)
    EXPECT_NE(std::find(widths.begin(), widths.end(), mode.packet), widths.end()) << mode.name();
  BenchParams params;
  params.base.scene = "wavy-sphere:triangles=300";
  for (int packet : {4, 8, 16}) {
    if (std::find(widths.begin(), widths.end(), packet) != widths.end()) continue;
    params.embree_modes = {{EmbreeBuild::kRefit, packet}};
    EXPECT_THROW(validate(params), InputError) << packet;
  }
}

}  // namespace
}  // namespace kinray
