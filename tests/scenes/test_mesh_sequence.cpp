// Mesh sequences: files written by the test into a folder, loaded through load_scene as a glob and
// as a folder, in natural order, with the keys at --keyrate, doubles kept exactly, and the file at
// fault named when a file is malformed or its topology differs.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "scenes/mesh_sequence.h"
#include "scenes/scene_loader.h"
#include "util/input_error.h"

namespace kinray {
namespace {

namespace fs = std::filesystem;

/// A strip of `n` quads in the plane z = height(frame), its x coordinates offset by a tiny amount
/// (1e-9, far below float resolution at 1) that only doubles keep.
std::vector<Vec3> strip(int n, int frame) {
  std::vector<Vec3> points;
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j < 2; ++j)
      points.emplace_back(1 + i + 1e-9 * (frame + 1), j, 0.25 * frame + 1e-10 * i);
  return points;
}

std::string format(double value) {
  char text[40];
  std::snprintf(text, sizeof text, "%.17g", value);
  return text;
}

void write_ply(const fs::path& path, int n, int frame) {
  std::ofstream file(path);
  const std::vector<Vec3> points = strip(n, frame);
  file << "ply\nformat ascii 1.0\nelement vertex " << points.size()
       << "\nproperty double x\nproperty double y\nproperty double z\nelement face " << n
       << "\nproperty list uchar int vertex_indices\nend_header\n";
  for (const Vec3& p : points)
    file << format(p.x()) << " " << format(p.y()) << " " << format(p.z()) << "\n";
  for (int i = 0; i < n; ++i)
    file << "4 " << 2 * i << " " << 2 * i + 2 << " " << 2 * i + 3 << " " << 2 * i + 1 << "\n";
}

/// Two objects: the strip and a copy of it lifted by 5.
void write_obj(const fs::path& path, int n, int frame) {
  std::ofstream file(path);
  const std::vector<Vec3> points = strip(n, frame);
  for (const char* name : {"lower", "upper"}) {
    const double lift = name[0] == 'u' ? 5 : 0;
    file << "o " << name << "\n";
    for (const Vec3& p : points)
      file << "v " << format(p.x()) << " " << format(p.y()) << " " << format(p.z() + lift) << "\n";
    for (int i = 0; i < n; ++i)  // relative indices: the last 2n+2 vertices are this object's
      file << "f " << 2 * i - int(points.size()) << "/1 " << 2 * i + 2 - int(points.size())
           << "//1 " << 2 * i + 3 - int(points.size()) << " " << 2 * i + 1 - int(points.size())
           << "\n";
  }
}

class MeshSequence : public ::testing::Test {
 protected:
  void SetUp() override {
    m_dir = fs::temp_directory_path() /
            ("kinray_sequence_" +
             std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) + "_" +
             std::to_string(::getpid()));
    fs::remove_all(m_dir);
    fs::create_directories(m_dir);
  }
  void TearDown() override { fs::remove_all(m_dir); }

  std::string error_of(const std::string& spec, const ModelOptions& options = {}) {
    try {
      (void)load_scene(spec, options);
    } catch (const InputError& error) {
      return error.what();
    }
    return "";
  }

  fs::path m_dir;
};

TEST_F(MeshSequence, NaturalOrderAndKeyrate) {
  EXPECT_TRUE(natural_less("frame_9.ply", "frame_10.ply"));
  EXPECT_FALSE(natural_less("frame_10.ply", "frame_9.ply"));
  EXPECT_TRUE(natural_less("frame_0009.ply", "frame_10.ply"));
  EXPECT_TRUE(natural_less("a2b3", "a2b10"));
  // frames 1, 2, 10 (lexicographic order would put 10 before 2)
  for (int frame : {1, 2, 10})
    write_ply(m_dir / ("frame_" + std::to_string(frame) + ".ply"), 3, frame);
  for (const std::string& spec : {(m_dir / "frame_*.ply").string(), m_dir.string()}) {
    SCOPED_TRACE(spec);
    ModelOptions options;
    options.keyrate = spec.back() == 'y' ? 0 : 10;
    const Scene scene = load_scene(spec, options);
    ASSERT_EQ(scene.objects.size(), 1u);
    const Object& object = scene.objects[0];
    EXPECT_EQ(object.triangles.size(), 6u);
    ASSERT_EQ(object.key_count(), 3u);
    const double rate = options.keyrate > 0 ? options.keyrate : 24;
    for (int k = 0; k < 3; ++k) EXPECT_DOUBLE_EQ(object.key_times[k], k / rate);
    EXPECT_EQ(scene.time_begin, 0);
    EXPECT_DOUBLE_EQ(scene.time_end, 2 / rate);
    const int frames[3] = {1, 2, 10};
    for (int k = 0; k < 3; ++k) EXPECT_EQ(object.key_positions[k], strip(3, frames[k]));
  }
}

TEST_F(MeshSequence, DoublesThatFloatsWouldRoundAreKeptExactly) {
  for (int frame = 0; frame < 2; ++frame)
    write_ply(m_dir / ("f" + std::to_string(frame) + ".ply"), 2, frame);
  const Scene scene = load_scene((m_dir / "f*.ply").string());
  const Vec3 p = scene.objects[0].key_positions[1][2];
  EXPECT_EQ(p, strip(2, 1)[2]);
  EXPECT_NE(double(float(p.x())), p.x());  // what an import through floats would have moved
  EXPECT_NE(double(float(p.z())), p.z());
}

TEST_F(MeshSequence, ObjObjectsBecomeObjects) {
  for (int frame : {3, 1, 2}) write_obj(m_dir / ("sim" + std::to_string(frame) + ".obj"), 4, frame);
  const Scene scene = load_scene(m_dir.string());
  ASSERT_EQ(scene.objects.size(), 2u);
  EXPECT_EQ(scene.objects[0].name, "lower");
  EXPECT_EQ(scene.objects[1].name, "upper");
  for (int k = 0; k < 3; ++k) {
    EXPECT_EQ(scene.objects[0].key_positions[k], strip(4, k + 1));
    EXPECT_EQ(scene.objects[1].key_positions[k][0], strip(4, k + 1)[0] + Vec3(0, 0, 5));
  }
  const std::vector<Triangle> first = {{0, 2, 3}, {0, 3, 1}};
  EXPECT_EQ(std::vector<Triangle>(scene.objects[1].triangles.begin(),
                                  scene.objects[1].triangles.begin() + 2),
            first);
}

TEST_F(MeshSequence, AFileOfAnotherTopologyIsNamed) {
  write_ply(m_dir / "frame_1.ply", 3, 1);
  write_ply(m_dir / "frame_2.ply", 3, 2);
  write_ply(m_dir / "frame_10.ply", 4, 10);
  EXPECT_EQ(error_of((m_dir / "frame_*.ply").string()),
            (m_dir / "frame_10.ply").string() +
                ": topology differs from the sequence's first file: mesh 0 has 10 vertices here, "
                "8 in the first file (frame_1.ply)");
  // the same counts, one triangle's corners in another order
  write_ply(m_dir / "frame_10.ply", 3, 10);
  std::string text;
  {
    std::ifstream in(m_dir / "frame_10.ply");
    text.assign(std::istreambuf_iterator<char>(in), {});
  }
  text.replace(text.rfind("4 4 6 7 5"), 9, "4 4 6 5 7");
  std::ofstream(m_dir / "frame_10.ply") << text;
  EXPECT_EQ(error_of(m_dir.string()),
            (m_dir / "frame_10.ply").string() +
                ": topology differs from the sequence's first file: mesh 0 triangle 4 is (4, 6, 5) "
                "here, (4, 6, 7) in the first file (frame_1.ply)");
}

TEST_F(MeshSequence, AMalformedLineIsNamedWithItsFile) {
  write_obj(m_dir / "a1.obj", 2, 1);
  write_obj(m_dir / "a2.obj", 2, 2);
  std::ofstream(m_dir / "a2.obj", std::ios::app) << "f 1 2 99\n";
  EXPECT_EQ(error_of(m_dir.string()),
            (m_dir / "a2.obj").string() + ":19: vertex index 99 out of range (12 vertices so far)");
}

TEST_F(MeshSequence, EmptyMixedAndForeignSequencesAreRefused) {
  EXPECT_EQ(error_of((m_dir / "none_*.ply").string()),
            (m_dir / "none_*.ply").string() + ": matches no files (an empty sequence)");
  EXPECT_EQ(error_of(m_dir.string()),
            m_dir.string() + ": holds no .ply or .obj files (an empty sequence)");
  write_ply(m_dir / "a1.ply", 1, 1);
  write_obj(m_dir / "a2.obj", 1, 2);
  EXPECT_NE(error_of(m_dir.string()).find("mixes .ply and .obj files"), std::string::npos);
  std::ofstream(m_dir / "a3.txt") << "x";
  EXPECT_EQ(error_of((m_dir / "a*").string()), (m_dir / "a*").string() + ": matches '" +
                                                   (m_dir / "a3.txt").string() +
                                                   "', which is neither a .ply nor an .obj file");
  EXPECT_EQ(error_of((m_dir / "*/x*.ply").string()),
            (m_dir / "*/x*.ply").string() +
                ": only the file name of a sequence pattern may hold wildcards");
  ModelOptions options;
  options.keyrate = -1;
  EXPECT_EQ(error_of((m_dir / "a*.ply").string(), options),
            "--keyrate: must be a number in [0, 1e6] (0: 24 keys per second)");
  ModelOptions animation;
  animation.animation = "walk";
  EXPECT_EQ(error_of((m_dir / "a*.ply").string(), animation),
            "--animation: applies to model files; a mesh sequence's animation is its files");
}

}  // namespace
}  // namespace kinray
