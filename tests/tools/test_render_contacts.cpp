// `kinray render --contacts`: on the built-in crossing, the tinted pixels of every frame are
// exactly the pixels of the triangles that `kinray collide --self` lists for the frame's window
// [t - h/2, t + h/2), with the kinetic backend and with Embree alike.
#include <gtest/gtest.h>

#include <algorithm>
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <set>

#include "renderer/frame.h"
#include "renderer/output/image_io.h"
#include "scenes/scene_loader.h"
#include "tests/tools/kinray_process.h"

namespace kinray {
namespace {

constexpr const char* kScene = "crossing:triangles=600";

/// The (object, triangle) pairs holding every vertex of `corners` of `object` (brute force).
void holding(const Scene& scene, uint32_t object, const std::vector<uint32_t>& corners,
             std::set<std::pair<uint32_t, uint32_t>>& out) {
  const std::vector<Triangle>& triangles = scene.objects[object].triangles;
  for (uint32_t t = 0; t < triangles.size(); ++t) {
    bool all = true;
    for (uint32_t v : corners)
      all = all && std::find(triangles[t].begin(), triangles[t].end(), v) != triangles[t].end();
    if (all) out.insert({object, t});
  }
}

class RenderContacts : public test::CommandTest {};

TEST_F(RenderContacts, TintedPixelsAreExactlyTheTrianglesCollideListsForTheFrame) {
  const test::CommandRun collide =
      kinray(std::string("collide ") + kScene + " --self -q --json " + path("contacts.json"));
  ASSERT_EQ(collide.status, 0) << collide.err;
  const nlohmann::json contacts =
      nlohmann::json::parse(test::read_text(path("contacts.json")))["contacts"];
  ASSERT_GT(contacts.size(), 0u);
  const Scene scene = load_scene(kScene);
  const int frames = 9;
  for (const char* backend : {"kinetic", "embree"}) {
    SCOPED_TRACE(backend);
    const std::string common = std::string("render ") + kScene + " --size 96x72 -q --frames " +
                               std::to_string(frames) + " --backend " + backend;
    const test::CommandRun tinted = kinray(common + " --contacts --aov id --out " + path("tinted") +
                                           " --stats " + path("stats.json"));
    ASSERT_EQ(tinted.status, 0) << tinted.err;
    const test::CommandRun plain = kinray(common + " --out " + path("plain"));
    ASSERT_EQ(plain.status, 0) << plain.err;
    const std::vector<double> times =
        nlohmann::json::parse(test::read_text(path("stats.json")))["frame_times"];
    ASSERT_EQ(times.size(), size_t(frames));
    const double h = times[1] - times[0];
    size_t tinted_pixels = 0, frames_with_contacts = 0;
    for (int f = 0; f < frames; ++f) {
      // the triangles of the contacts in [t - h/2, t + h/2), straight from collide's list
      std::set<std::pair<uint32_t, uint32_t>> expected;
      for (const nlohmann::json& c : contacts) {
        const double time = c["time"];
        const bool last = f == frames - 1;
        if (!(time >= times[f] - h / 2 &&
              (time < times[f] + h / 2 || (last && time <= times[f] + h / 2))))
          continue;
        const std::vector<uint32_t> v = c["vertices"], objects = c["objects"];
        const bool vf = c["type"] == "vf";
        holding(scene, objects[0],
                vf ? std::vector<uint32_t>{v[0]} : std::vector<uint32_t>{v[0], v[1]}, expected);
        holding(scene, objects[1],
                vf ? std::vector<uint32_t>{v[1], v[2], v[3]} : std::vector<uint32_t>{v[2], v[3]},
                expected);
      }
      frames_with_contacts += !expected.empty();
      char name[32];
      std::snprintf(name, sizeof name, "%05d", f);
      Frame ids;
      read_id_png(path("tinted/id_" + std::string(name) + ".png"), ids);
      const cv::Mat a = read_color_png(path("tinted/frame_" + std::string(name) + ".png"));
      const cv::Mat b = read_color_png(path("plain/frame_" + std::string(name) + ".png"));
      size_t wrong = 0;
      for (int j = 0; j < ids.height; ++j)
        for (int i = 0; i < ids.width; ++i) {
          const size_t p = ids.index(i, j);
          const bool is_tinted = a.at<cv::Vec3b>(j, i) != b.at<cv::Vec3b>(j, i);
          const bool in_contact =
              ids.object[p] != kNoHit && expected.count({ids.object[p], ids.prim[p]}) > 0;
          tinted_pixels += is_tinted;
          wrong += is_tinted != in_contact;
        }
      EXPECT_EQ(wrong, 0u) << "frame " << f << " at t = " << times[f];
    }
    EXPECT_GT(tinted_pixels, 50u);
    EXPECT_GT(frames_with_contacts, 0u);
    EXPECT_LT(frames_with_contacts, size_t(frames));  // the spheres touch only while crossing
  }
}

TEST_F(RenderContacts, MotionBlurIsRefused) {
  const test::CommandRun run =
      kinray(std::string("render ") + kScene + " --contacts --shutter 0.5 --out " + path("out"));
  EXPECT_EQ(run.status, 2);
  EXPECT_EQ(run.err,
            "kinray: error: --contacts: tints sharp frames; drop --shutter (motion blur) or "
            "--contacts\n");
}

}  // namespace
}  // namespace kinray
