// Soak: the kinetic grid of a built-in scene through thousands of small frames, as a long render
// runs it. Every frame is read out; every 100th is audited by brute force (every record, slot,
// interval, pixel set and certificate, FrustumGrid::audit); and the memory must stay flat: the
// grid's own count of its bytes and the process's resident set, measured once the grid has
// settled (a tenth of the way in) and at the end. A leak per frame or per event, or a structure
// that grows with the number of frames rendered, fails here long before a user's render runs
// out of memory.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

#include "kinetic/grid/frustum_grid.h"
#include "renderer/backends/kinetic_backend.h"
#include "scenes/camera_space.h"
#include "scenes/scene_loader.h"
#include "tests/address_sanitizer.h"

namespace kinray {
namespace {

/// The process's resident set in bytes (second field of /proc/self/statm, in pages).
size_t resident_bytes() {
  size_t size = 0, resident = 0;
  std::ifstream("/proc/self/statm") >> size >> resident;
  return resident * size_t(sysconf(_SC_PAGESIZE));
}

struct SoakCase {
  const char* spec;
  int frames;
};

class Soak : public ::testing::TestWithParam<SoakCase> {};

INSTANTIATE_TEST_SUITE_P(BuiltIns, Soak,
                         ::testing::Values(SoakCase{"wavy-sphere:triangles=8000,duration=12", 6000},
                                           SoakCase{"orbit", 3000}),
                         [](const auto& param) {
                           std::string name = param.param.spec;
                           name = name.substr(0, name.find(':'));
                           std::replace(name.begin(), name.end(), '-', '_');
                           return name;
                         });

TEST_P(Soak, ThousandsOfFramesAuditedWithFlatMemory) {
  constexpr int kWidth = 48, kHeight = 36, kAuditEvery = 100;
  const Scene scene = load_scene(GetParam().spec);
  const CameraSpaceScene cs = CameraSpaceScene::build(scene);
  FrustumGridConfig config;
  config.threads = 2;
  const double t0 = scene.time_begin, t1 = scene.time_end;
  const int frames = GetParam().frames, settled = frames / 10;
  FrustumGrid grid(kinetic_grid_input(cs, kWidth, kHeight), t0, config);
  const size_t pixels = size_t(kWidth) * kHeight;
  std::vector<uint32_t> object(pixels), prim(pixels);
  std::vector<float> depth(pixels);
  // The edge normals are a cache by edge whose pages are written as the bands meet edges: it
  // fills up to its table over the shot and is followed apart from the rest of the grid.
  size_t covered = 0, audits = 0, grid_bytes_settled = 0, rss_settled = 0, grid_bytes_max = 0;
  size_t normals_settled = 0, normals_end = 0;
  for (int f = 0; f < frames; ++f) {
    grid.advance_to(t0 + (t1 - t0) * f / (frames - 1));
    grid.read_out(object, prim, depth);
    covered += size_t(
        std::count_if(object.begin(), object.end(), [](uint32_t o) { return o != kNoGridHit; }));
    if (f % kAuditEvery != 0 && f != frames - 1 && f != settled) continue;
    const std::vector<std::string> problems = grid.audit();
    ASSERT_TRUE(problems.empty()) << "frame " << f << ": " << problems.front();
    ++audits;
    const GridStats stats = grid.stats();
    const size_t grid_bytes = stats.memory_bytes - stats.edge_normal_bytes;
    normals_end = stats.edge_normal_bytes;
    if (f >= settled) grid_bytes_max = std::max(grid_bytes_max, grid_bytes);
    if (f == settled) {
      grid_bytes_settled = grid_bytes;
      normals_settled = stats.edge_normal_bytes;
      rss_settled = resident_bytes();
    }
  }
  const size_t rss_end = resident_bytes();
  const uint64_t events = grid.event_count();
  std::cout << GetParam().spec << ": " << frames << " frames, " << events << " events, " << audits
            << " audits; grid " << grid_bytes_settled << " -> at most " << grid_bytes_max
            << " bytes and edge normals " << normals_settled << " -> " << normals_end
            << " bytes, resident " << rss_settled << " -> " << rss_end << " bytes\n";
  EXPECT_GT(events, 1000u) << "the scene must keep the grid busy";
  EXPECT_GT(covered, size_t(frames) * pixels / 50) << "the scene must be in view";
  EXPECT_GE(audits, size_t(frames / kAuditEvery));
  // The grid's structures follow the geometry, which stays the same size: at most a quarter more
  // than when it settled (records and certificates come and go as triangles cross pixels).
  EXPECT_LE(grid_bytes_max, grid_bytes_settled + grid_bytes_settled / 4)
      << "grid memory grew from " << grid_bytes_settled << " to " << grid_bytes_max << " bytes";
#ifndef KINRAY_UNDER_ADDRESS_SANITIZER
  // The process: within 4 MiB of the settled resident set (allocator slack, and what the grid's
  // own growth above explains), and the edge normals' pages written since.
  EXPECT_LE(rss_end, rss_settled + (size_t(4) << 20) + (normals_end - normals_settled))
      << "resident set grew from " << rss_settled << " to " << rss_end << " bytes over "
      << frames - settled << " frames, " << events << " events";
#else
  // AddressSanitizer keeps freed memory in quarantine (256 MiB), so the resident set grows by
  // design; LeakSanitizer checks for leaks at exit instead.
  (void)rss_settled;
  (void)rss_end;
#endif
}

}  // namespace
}  // namespace kinray
