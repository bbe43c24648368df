// What `kinray render` shows on a terminal before and while it renders: a note while the scene
// loads and while the kinetic grid is initialised (seconds for millions of triangles), then the
// bar; nothing with --quiet; an error after the note still on a line of its own.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "tests/address_sanitizer.h"
#include "tests/tools/kinray_process.h"
#include "tests/tools/terminal_run.h"

namespace kinray {
namespace {

class CliRenderTerminal : public test::CommandTest {
 protected:
  [[nodiscard]] test::CommandRun on_terminal(const std::string& args) const {
    return test::run_kinray_on_terminal(args, m_dir);
  }
};

/// What a terminal shows last: the text after the last carriage return, less erase-line codes.
std::string last_visible_line(std::string text) {
  while (!text.empty() && (text.back() == '\n' || text.back() == '\r')) text.pop_back();
  text = text.substr(text.rfind('\r') == std::string::npos ? 0 : text.rfind('\r') + 1);
  for (size_t at; (at = text.find("\033[K")) != std::string::npos;) text.erase(at, 3);
  return text;
}

TEST_F(CliRenderTerminal, NotesLoadingAndGridInitialisationThenDrawsTheBar) {
  const test::CommandRun run = on_terminal(
      "render --backend kinetic wavy-sphere:triangles=600 --size 64x48 --frames 3 --out '" + path("frames") + "'");
  ASSERT_EQ(run.status, 0) << run.err;
  const size_t loading = run.err.find("loading wavy-sphere:triangles=600...");
  const size_t grid = run.err.find("initialising the kinetic grid...");
  const size_t bar = run.err.find("3/3 frames");
  ASSERT_NE(loading, std::string::npos) << run.err;
  ASSERT_NE(grid, std::string::npos) << run.err;
  ASSERT_NE(bar, std::string::npos) << run.err;
  EXPECT_LT(loading, grid);
  EXPECT_LT(grid, bar);
  // The bar is cleared at the end: the terminal's last line is empty, the summary is on stdout.
  EXPECT_EQ(last_visible_line(run.err), "");
  EXPECT_NE(run.out.find("rendered 3 frames of wavy-sphere:triangles=600"), std::string::npos)
      << run.out;
}

TEST_F(CliRenderTerminal, AGridThatTakesSecondsToInitialiseShowsHowFarItHasGot) {
  // 300,000 triangles: the culling proof and the scan conversion take well over the 250 ms
  // between redraws (a seventh of them under AddressSanitizer, which runs several times slower).
  const std::string triangles = test::kUnderAddressSanitizer ? "40000" : "300000";
  const test::CommandRun run =
      on_terminal("render --backend kinetic wavy-sphere:triangles=" + triangles +
                  " --size 320x240 --frames 1 --threads 1 --out '" + path("frames") + "'");
  ASSERT_EQ(run.status, 0) << run.err;
  // Two steps, each with its share done, which only grows within the step.
  int shown = 0;
  for (const std::string step : {"back-face culling proof ", "scan conversion "}) {
    const std::string note = "initialising the kinetic grid... " + step;
    int last = -1;
    for (size_t at = run.err.find(note); at != std::string::npos; at = run.err.find(note, at + 1)) {
      const size_t digits = at + note.size();
      const size_t percent = run.err.find('%', digits);
      ASSERT_NE(percent, std::string::npos) << run.err;
      ASSERT_LE(percent - digits, 3u) << run.err;
      const int value = std::stoi(run.err.substr(digits, percent - digits));
      EXPECT_GE(value, last) << run.err;
      EXPECT_LE(value, 100);
      last = value;
      ++shown;
    }
  }
  EXPECT_GT(shown, 0) << run.err;
  EXPECT_NE(run.err.find(" s\033[K"), std::string::npos) << run.err;  // with its elapsed time
  EXPECT_EQ(last_visible_line(run.err), "");
}

TEST_F(CliRenderTerminal, EmbreeHasNoGridToInitialise) {
  const test::CommandRun run = on_terminal(
      "render wavy-sphere:triangles=600 --size 64x48 --frames 2 --backend embree --out '" +
      path("frames") + "'");
  ASSERT_EQ(run.status, 0) << run.err;
  EXPECT_NE(run.err.find("loading wavy-sphere:triangles=600..."), std::string::npos) << run.err;
  EXPECT_EQ(run.err.find("kinetic grid"), std::string::npos) << run.err;
  EXPECT_NE(run.err.find("2/2 frames"), std::string::npos) << run.err;
}

TEST_F(CliRenderTerminal, QuietShowsNothing) {
  const test::CommandRun run = on_terminal(
      "render wavy-sphere:triangles=600 --size 64x48 --frames 3 -q --out '" + path("frames") + "'");
  ASSERT_EQ(run.status, 0) << run.err;
  EXPECT_EQ(run.err, "");
  EXPECT_EQ(run.out, "");
}

TEST_F(CliRenderTerminal, AnErrorWhileLoadingIsOneCleanLine) {
  std::ofstream(path("far.json")) << R"({"shot": {"begin": 0, "end": 1},
    "camera": {"keys": [{"time": 0, "position": [0, 0, -5], "look_at": [0, 0, 0], "fov_y": 45}]},
    "objects": [{"kind": "mesh", "triangles": [[0, 1, 2]],
      "keys": [{"time": 0, "vertices": [[-1, -1, 0], [1, -1, 0], [0, 1e300, 3]]}]}]})";
  const test::CommandRun run = on_terminal(
      "render '" + path("far.json") + "' --size 32x32 --frames 1 --out '" + path("frames") + "'");
  EXPECT_EQ(run.status, 2) << run.err;
  EXPECT_NE(run.err.find("loading "), std::string::npos) << run.err;  // the note was drawn
  // ... and erased before the error, which stands alone on the terminal's last line.
  const std::string line = last_visible_line(run.err);
  EXPECT_EQ(line.rfind("kinray: error: ", 0), 0u) << line;
  EXPECT_NE(line.find("far.json: object 0"), std::string::npos) << line;
  EXPECT_NE(line.find("vertex 2 at key 0 has a coordinate beyond +-1e15"), std::string::npos)
      << line;
  EXPECT_FALSE(std::filesystem::exists(path("frames")));
}

}  // namespace
}  // namespace kinray
