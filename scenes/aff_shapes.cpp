#include "scenes/aff_shapes.h"

#include <algorithm>
#include <unordered_map>

#include "scenes/aff_tessellate.h"

namespace kinray {
namespace {

constexpr int kMaxCount = 50'000'000;

Vec3 read_vec3(AffReader& in, const char* what) {
  double xyz[3];
  in.numbers(xyz, 3, what);
  return {xyz[0], xyz[1], xyz[2]};
}

Vec2f read_uv(AffReader& in) {
  const double u = in.number("a texture coordinate u"), v = in.number("a texture coordinate v");
  return {float(u), float(v)};
}

AffShapeRead static_shape(const std::string& where, std::vector<Vec3> positions,
                          std::vector<Triangle> triangles) {
  AffShapeRead read;
  read.shape.where = where;
  read.shape.key_positions = {std::move(positions)};
  read.shape.triangles = std::move(triangles);
  return read;
}

/// The `triangles N` section: three vertex indices each, then normal and texture-coordinate
/// indices when the mesh has those; corners with different texture coordinates get their own
/// vertex.
void read_mesh_triangles(AffReader& in, const std::vector<Vec3>& vertices, size_t normal_count,
                         const std::vector<Vec2f>& uvs, AffShape& shape) {
  const int count = in.integer("the triangle count", 0, kMaxCount);
  auto index = [&in](const char* what, size_t limit) {
    const int i = in.integer(what, 0, kMaxCount);
    if (size_t(i) >= limit)
      in.fail(std::string(what) + " " + std::to_string(i) + " is out of range (the mesh has " +
              std::to_string(limit) + ")");
    return uint32_t(i);
  };
  std::unordered_map<uint64_t, uint32_t> corner_vertex;  // (vertex, uv) -> split vertex
  std::vector<Vec3>& positions = shape.key_positions[0];
  if (uvs.empty()) positions = vertices;
  for (int f = 0; f < count; ++f) {
    Triangle v{}, t{};
    for (uint32_t& i : v) i = index("a vertex index", vertices.size());
    for (int c = 0; c < 3 && normal_count > 0; ++c) (void)index("a normal index", normal_count);
    if (uvs.empty()) {
      shape.triangles.push_back(v);
      continue;
    }
    for (uint32_t& i : t) i = index("a texture-coordinate index", uvs.size());
    Triangle corners{};
    for (int c = 0; c < 3; ++c) {
      const uint64_t key = (uint64_t(v[c]) << 32) | t[c];
      const auto [it, inserted] = corner_vertex.emplace(key, uint32_t(positions.size()));
      if (inserted) {
        positions.push_back(vertices[v[c]]);
        shape.uvs.push_back(uvs[t[c]]);
      }
      corners[c] = it->second;
    }
    shape.triangles.push_back(corners);
  }
}

}  // namespace

AffShapeRead read_mesh(AffReader& in) {
  AffShapeRead read = static_shape(in.where(), {}, {});
  std::vector<Vec3> vertices;
  std::vector<Vec2f> uvs;
  size_t normal_count = 0;
  bool has_vertices = false, has_normals = false, has_uvs = false;
  for (;;) {
    const std::string section =
        in.word("a mesh section (vertices, normals, texturecoords or triangles)");
    if (section == "vertices" || section == "normals") {
      bool& given = section == "vertices" ? has_vertices : has_normals;
      if (given) in.fail("the mesh gives " + section + " twice");
      given = true;
      const int count =
          in.integer(section == "vertices" ? "the vertex count" : "the normal count", 0, kMaxCount);
      for (int k = 0; k < count; ++k) {
        const Vec3 value = read_vec3(in, section == "vertices" ? "a vertex" : "a normal");
        if (section == "vertices") vertices.push_back(value);
      }
      if (section == "normals") normal_count = size_t(count);
    } else if (section == "texturecoords") {
      if (has_uvs) in.fail("the mesh gives texturecoords twice");
      has_uvs = true;
      const int count = in.integer("the texture-coordinate count", 0, kMaxCount);
      read.texture = in.word("a texture file name");
      for (int k = 0; k < count; ++k) uvs.push_back(read_uv(in));
    } else if (section == "triangles") {
      if (!has_vertices) in.fail("the mesh's triangles come before its vertices");
      if (has_normals && normal_count == 0) has_normals = false;
      if (has_uvs && uvs.empty())
        in.fail("the mesh names a texture but gives no texture coordinates");
      read_mesh_triangles(in, vertices, normal_count, uvs, read.shape);
      return read;
    } else {
      in.fail("unknown mesh section '" + section +
              "' (expected vertices, normals, texturecoords or triangles)");
    }
  }
}

AffShapeRead read_polygon(AffReader& in, bool patch) {
  const std::string where = in.where();
  const int count = in.integer("the polygon's vertex count", 3, kMaxCount);
  std::vector<Vec3> positions;
  for (int k = 0; k < count; ++k) {
    positions.push_back(read_vec3(in, "a polygon vertex"));
    if (patch) (void)read_vec3(in, "a patch normal");
  }
  return static_shape(where, std::move(positions), fan_triangles(size_t(count)));
}

AffShapeRead read_textured_triangle(AffReader& in, bool patch) {
  const std::string where = in.where();
  std::string texture = in.word("a texture file name");
  std::vector<Vec3> positions;
  std::vector<Vec2f> uvs;
  for (int k = 0; k < 3; ++k) {
    positions.push_back(read_vec3(in, "a triangle vertex"));
    if (patch) (void)read_vec3(in, "a patch normal");
    uvs.push_back(read_uv(in));
  }
  AffShapeRead read = static_shape(where, std::move(positions), {{0, 1, 2}});
  read.shape.uvs = std::move(uvs);
  read.texture = std::move(texture);
  return read;
}

AffShapeRead read_animated_triangle(AffReader& in) {
  const std::string where = in.where();
  const int count = in.integer("the number of keys of the animated triangle", 1, kMaxCount);
  AffShapeRead read = static_shape(where, {}, {{0, 1, 2}});
  read.shape.key_times.clear();
  read.shape.key_positions.clear();
  for (int k = 0; k < count; ++k) {
    const double time = in.number("a key time");
    if (!read.shape.key_times.empty() && !(time > read.shape.key_times.back()))
      in.fail("the key times of an animated triangle must increase");
    std::vector<Vec3> corners;
    for (int c = 0; c < 3; ++c) {
      corners.push_back(read_vec3(in, "a triangle vertex"));
      (void)read_vec3(in, "a triangle normal");
    }
    read.shape.key_times.push_back(time);
    read.shape.key_positions.push_back(std::move(corners));
  }
  return read;
}

AffShapeRead read_cone(AffReader& in) {
  const std::string where = in.where();
  const Vec3 base = read_vec3(in, "the cone's base");
  double base_radius = in.number("the base radius");
  const Vec3 apex = read_vec3(in, "the cone's apex");
  double apex_radius = in.number("the apex radius");
  const bool inside = base_radius < 0;  // NFF: negative radii show the inside
  if (inside) base_radius = -base_radius, apex_radius = -apex_radius;
  if (apex_radius < 0) in.fail("the cone's radii must have the same sign");
  if (base_radius == 0 && apex_radius == 0) in.fail("the cone has zero radii");
  if (base == apex) in.fail("the cone's base and apex coincide");
  TriangleMesh mesh = tessellate_cone(base, base_radius, apex, apex_radius);
  if (inside)
    for (Triangle& t : mesh.triangles) std::swap(t[1], t[2]);
  return static_shape(where, std::move(mesh.positions), std::move(mesh.triangles));
}

AffShapeRead read_sphere(AffReader& in) {
  const std::string where = in.where();
  const Vec3 center = read_vec3(in, "the sphere's center");
  const double radius = in.number("the sphere's radius");
  if (radius == 0) in.fail("the sphere's radius is 0");
  TriangleMesh mesh = tessellate_sphere(center, std::abs(radius));
  if (radius < 0)
    for (Triangle& t : mesh.triangles) std::swap(t[1], t[2]);
  return static_shape(where, std::move(mesh.positions), std::move(mesh.triangles));
}

}  // namespace kinray
