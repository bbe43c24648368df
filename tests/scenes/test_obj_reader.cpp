// The OBJ reader of mesh sequences: the v/vt/vn corner forms, negative indices, polygons fanned,
// objects and groups as meshes of their own, doubles kept exactly, and bad input at file:line.
#include <gtest/gtest.h>

#include <string>

#include "scenes/obj_reader.h"
#include "util/input_error.h"

namespace kinray {
namespace {

TEST(ObjReader, CornerFormsNegativeIndicesAndFans) {
  const std::string text =
      "# a quad and a triangle\nmtllib x.mtl\nv 0.1 0.2 0.3\nv 1.0000000000000002 0 0 1\n"
      "v 1 1 0 0.5 0.5 0.5\nv 0 1 123456789.123456789\nvt 0 0\nvn 0 0 1\nusemtl red\ns off\n"
      "f 1/1/1 2/1/1 3//1 4\nf -4 -2 -1\n";
  const MeshFile file = parse_obj(text, "a.obj");
  ASSERT_EQ(file.parts.size(), 1u);
  const MeshPart& part = file.parts[0];
  EXPECT_EQ(part.name, "");
  ASSERT_EQ(part.positions.size(), 4u);
  EXPECT_EQ(part.positions[0], Vec3(0.1, 0.2, 0.3));
  EXPECT_EQ(part.positions[1].x(), 1.0000000000000002);
  EXPECT_EQ(part.positions[3].z(), 123456789.123456789);
  const std::vector<Triangle> expected = {{0, 1, 2}, {0, 2, 3}, {0, 2, 3}};
  EXPECT_EQ(part.triangles, expected);
}

TEST(ObjReader, ObjectsAndGroupsAreMeshesInTheirOwnNumbering) {
  const std::string text =
      "o left\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"
      "g right\nv 5 0 0\nv 6 0 0\nv 5 1 0\nv 6 1 0\nf 4 5 7 6\n"
      "o unused\ng left\nf 1 3 2\n";
  const MeshFile file = parse_obj(text, "b.obj");
  ASSERT_EQ(file.parts.size(), 2u);
  EXPECT_EQ(file.parts[0].name, "left");
  EXPECT_EQ(file.parts[0].positions.size(), 3u);
  const std::vector<Triangle> left = {{0, 1, 2}, {0, 2, 1}};
  EXPECT_EQ(file.parts[0].triangles, left);
  EXPECT_EQ(file.parts[1].name, "right");
  ASSERT_EQ(file.parts[1].positions.size(), 4u);
  EXPECT_EQ(file.parts[1].positions[0], Vec3(5, 0, 0));
  const std::vector<Triangle> right = {{0, 1, 3}, {0, 3, 2}};
  EXPECT_EQ(file.parts[1].triangles, right);
}

std::string error_of(const std::string& text) {
  try {
    (void)parse_obj(text, "bad.obj");
  } catch (const InputError& error) {
    return error.what();
  }
  return "";
}

TEST(ObjReader, MalformedInputNamesFileAndLine) {
  const std::string v = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
  EXPECT_EQ(error_of(v + "f 1 2 4\n"),
            "bad.obj:4: vertex index 4 out of range (3 vertices so far)");
  EXPECT_EQ(error_of(v + "f 1 2 0\n"),
            "bad.obj:4: vertex index 0 out of range (3 vertices so far)");
  EXPECT_EQ(error_of(v + "f -4 1 2\n"),
            "bad.obj:4: vertex index -4 out of range (3 vertices so far)");
  EXPECT_EQ(error_of(v + "f 1 2\n"), "bad.obj:4: a face needs at least 3 corners, got 2");
  EXPECT_EQ(error_of(v + "f 1 a/2 3\n"),
            "bad.obj:4: expected a vertex index (i, i/t, i//n or i/t/n), got 'a/2'");
  EXPECT_EQ(
      error_of("v 0 0\n"),
      "bad.obj:1: a 'v' line needs x y z (optionally w, or a colour r g b [a]), got 2 values");
  EXPECT_EQ(error_of("v 0 0 0\nv 0 x 0\n"), "bad.obj:2: expected a number, got 'x'");
  EXPECT_EQ(error_of("v 0 0 0\n\nv 0 nan 0\n"), "bad.obj:3: coordinate y is NaN or infinite");
  EXPECT_EQ(error_of("v 0 0 1e16\n"),
            "bad.obj:1: coordinate z = 1e+16 lies beyond +-1e15, which the float references "
            "cannot trace");
  EXPECT_EQ(error_of(v), "bad.obj: has no faces");
}

}  // namespace
}  // namespace kinray
