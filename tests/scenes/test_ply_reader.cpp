// The PLY reader of mesh sequences: ascii and binary bodies of either byte order, float and double
// coordinates kept exactly, polygons fanned, and malformed input refused at file:line.
#include <gtest/gtest.h>

#include <bit>
#include <cstring>
#include <limits>
#include <string>

#include "scenes/ply_reader.h"
#include "util/input_error.h"

namespace kinray {
namespace {

/// The value's bytes in the given byte order.
template <typename T>
std::string raw(T value, bool big_endian) {
  std::string bytes(sizeof(T), '\0');
  std::memcpy(bytes.data(), &value, sizeof(T));
  if (big_endian != (std::endian::native == std::endian::big))
    std::reverse(bytes.begin(), bytes.end());
  return bytes;
}

/// A quad (0, 1, 2, 3) and a triangle (1, 4, 2) over five vertices, in double or float.
std::string binary_ply(bool big_endian, bool doubles, const double (&xyz)[5][3]) {
  const char* type = doubles ? "double" : "float";
  std::string text = std::string("ply\nformat ") +
                     (big_endian ? "binary_big_endian" : "binary_little_endian") +
                     " 1.0\ncomment written by a test\nelement vertex 5\nproperty " + type +
                     " x\nproperty " + type + " y\nproperty " + type +
                     " z\nproperty uchar red\nelement face 2\nproperty list uchar int "
                     "vertex_indices\nend_header\n";
  for (const auto& p : xyz) {
    for (double c : p) text += doubles ? raw(c, big_endian) : raw(float(c), big_endian);
    text += raw(uint8_t(200), big_endian);
  }
  text += raw(uint8_t(4), big_endian);
  for (int32_t v : {0, 1, 2, 3}) text += raw(v, big_endian);
  text += raw(uint8_t(3), big_endian);
  for (int32_t v : {1, 4, 2}) text += raw(v, big_endian);
  return text;
}

constexpr double kPoints[5][3] = {{0.1, 0.2, 0.3},
                                  {1 + 1e-12, 0, -2.5},
                                  {1, 1, 1e-300},
                                  {0, 1, -0.0},
                                  {123456789.123456789, 2, 3}};

TEST(PlyReader, BinaryBodiesOfBothByteOrdersKeepDoublesExactly) {
  for (const bool big : {false, true}) {
    SCOPED_TRACE(big ? "big endian" : "little endian");
    const MeshFile file = parse_ply(binary_ply(big, true, kPoints), "mesh.ply");
    ASSERT_EQ(file.parts.size(), 1u);
    const MeshPart& part = file.parts[0];
    ASSERT_EQ(part.positions.size(), 5u);
    for (int v = 0; v < 5; ++v)
      for (int a = 0; a < 3; ++a) EXPECT_EQ(part.positions[v][a], kPoints[v][a]);
    // the quad is fanned from its first corner
    const std::vector<Triangle> expected = {{0, 1, 2}, {0, 2, 3}, {1, 4, 2}};
    EXPECT_EQ(part.triangles, expected);
  }
}

TEST(PlyReader, FloatCoordinatesAreTheFloatValues) {
  const MeshFile file = parse_ply(binary_ply(false, false, kPoints), "mesh.ply");
  for (int v = 0; v < 5; ++v)
    for (int a = 0; a < 3; ++a)
      EXPECT_EQ(file.parts[0].positions[v][a], double(float(kPoints[v][a])));
}

TEST(PlyReader, AsciiBodyWithOtherElementsAndProperties) {
  const std::string text =
      "ply\r\nformat ascii 1.0\r\nelement vertex 4\r\nproperty double x\r\nproperty double y\r\n"
      "property double z\r\nproperty list uchar float extra\r\nelement edge 1\r\nproperty int a\r\n"
      "property int b\r\nelement face 1\r\nproperty uchar flags\r\nproperty list uchar uint "
      "vertex_index\r\nend_header\r\n"
      "0.1000000000000000055511151231257827 0 0 2 9 9\r\n1 0 0 0\r\n1 1 0 0\r\n"
      "0 1 1.0000000000000002 1 5\r\n0 1\r\n7 4 3 2 1 0\r\n";
  const MeshFile file = parse_ply(text, "a.ply");
  const MeshPart& part = file.parts[0];
  ASSERT_EQ(part.positions.size(), 4u);
  EXPECT_EQ(part.positions[0].x(), 0.1);
  EXPECT_EQ(part.positions[3].z(), 1.0000000000000002);
  const std::vector<Triangle> expected = {{3, 2, 1}, {3, 1, 0}};
  EXPECT_EQ(part.triangles, expected);
}

/// The one-line message of the InputError that parsing `text` throws ("" if none).
std::string error_of(const std::string& text) {
  try {
    (void)parse_ply(text, "bad.ply");
  } catch (const InputError& error) {
    return error.what();
  }
  return "";
}

const std::string kHeader =
    "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
    "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";

TEST(PlyReader, MalformedInputNamesFileAndLine) {
  EXPECT_EQ(error_of(kHeader + "0 0 0\n1 0 0\n0 1 zero\n3 0 1 2\n"),
            "bad.ply:12: expected a number, got 'zero'");
  EXPECT_EQ(error_of(kHeader + "0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n"),
            "bad.ply:13: vertex index 3 out of range (3 vertices)");
  EXPECT_EQ(error_of(kHeader + "0 0 0\n1 0 0\n0 1 0\n3 0 -1 2\n"),
            "bad.ply:13: a vertex index must be a non-negative integer");
  EXPECT_EQ(error_of(kHeader + "0 0 0\n1 0 0\n0 1 0\n2 0 1\n"),
            "bad.ply:13: face 0 has 2 corners; a face needs at least 3");
  EXPECT_EQ(error_of(kHeader + "0 0 0\n1 0 0\n0 1 0\n3 0 1\n"),
            "bad.ply:13: the file ends early: more values are declared");
  EXPECT_EQ(error_of(kHeader + "0 0 nan\n1 0 0\n0 1 0\n3 0 1 2\n"),
            "bad.ply:10: coordinate z is NaN or infinite");
  EXPECT_EQ(error_of(kHeader + "0 -inf 0\n1 0 0\n0 1 0\n3 0 1 2\n"),
            "bad.ply:10: coordinate y is NaN or infinite");
  EXPECT_EQ(error_of(kHeader + "2e15 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"),
            "bad.ply:10: coordinate x = 2e+15 lies beyond +-1e15, which the float references "
            "cannot trace");
  EXPECT_EQ(error_of("ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty "
                     "float y\nend_header\n0 0\n"),
            "bad.ply:3: the vertex element has no scalar property 'z'");
  EXPECT_EQ(error_of("ply\nformat ascii 2.0\n"),
            "bad.ply:2: expected 'format ascii|binary_little_endian|binary_big_endian 1.0'");
  EXPECT_EQ(error_of("ply\nformat ascii 1.0\nelement vertex 3\nproperty fixed x\n"),
            "bad.ply:4: unknown property type 'fixed'");
  EXPECT_EQ(error_of("ply\nformat ascii 1.0\n"), "bad.ply:3: the header ends without 'end_header'");
  EXPECT_EQ(error_of("solid cube\n"), "bad.ply:1: not a PLY file (no 'ply' line)");
  EXPECT_EQ(error_of(kHeader.substr(0, kHeader.find("element face")) +
                     "end_header\n0 0 0\n1 0 0\n0 1 0\n"),
            "bad.ply: has no faces (a 'face' element with a 'vertex_indices' list)");
}

TEST(PlyReader, CountsBeyondTheFileAreRefusedBeforeAnythingIsReserved) {
  std::string text = binary_ply(false, true, kPoints);
  text.replace(text.find("vertex 5"), 8, "vertex 4000000000");
  EXPECT_EQ(error_of(text).rfind("bad.ply:4: declares 4000000000 vertex elements", 0), 0u)
      << error_of(text);
  std::string truncated = binary_ply(true, true, kPoints);
  truncated.resize(truncated.size() - 3);
  EXPECT_NE(error_of(truncated).find("a face of 3 corners runs past the end of the file"),
            std::string::npos);
  EXPECT_EQ(error_of(truncated).rfind("bad.ply: byte ", 0), 0u) << error_of(truncated);
  // A vertex element with no properties takes no bytes, so no length of file bounds its count;
  // read as a second vertex element it would reserve 7e12 vertices (found by fuzz_ply_reader).
  EXPECT_EQ(error_of("ply\nformat ascii 1.0\nelement vertex 7000000000000\n" +
                     kHeader.substr(kHeader.find("element vertex")) +
                     "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"),
            "bad.ply:4: a second 'vertex' element (the first is on line 3)");
}

}  // namespace
}  // namespace kinray
