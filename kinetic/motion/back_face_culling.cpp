#include "kinetic/motion/back_face_culling.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <numeric>
#include <span>
#include <vector>

#include <Eigen/Geometry>

#include "kinetic/core/polynomial.h"
#include "util/parallel.h"

namespace kinray {

namespace {

using Vec = Eigen::Vector3d;
using Triangle = std::array<uint32_t, 3>;

// Rounding moves a determinant of vectors of lengths a, b, c by a few 1e-16 a b c, and the grid
// and Embree each place a vertex within an ulp or two of its chord: a coefficient must clear
// 1e-12 a b c, so the proved sign holds for every surface either of them actually sees.
constexpr double kRelativeMargin = 1e-12;
// Halvings of [0, 1] before a cubic whose Bernstein coefficients are not all of one sign is given
// up on (16 pieces).
constexpr int kSubdivisionDepth = 4;

// Work items per block of the parallel loops: a fixed partition, so that no result depends on
// the number of threads.
constexpr size_t kBlock = 4096;

size_t block_count(size_t n) { return (n + kBlock - 1) / kBlock; }

// Whether pred(i) holds for every i in [0, n), tried in parallel blocks.
template <class Pred>
bool all_of_parallel(size_t n, int threads, Pred&& pred) {
  std::vector<char> ok(block_count(n), 1);
  parallel_for_dynamic(ok.size(), threads, [&](size_t b) {
    for (size_t i = b * kBlock, end = std::min(n, (b + 1) * kBlock); i < end && ok[b]; ++i) ok[b] = pred(i);
  });
  return std::all_of(ok.begin(), ok.end(), [](char o) { return o != 0; });
}

// std::sort in pieces on the workers, then merged: the sorted order is unique.
void parallel_sort(std::vector<uint64_t>& values, int threads) {
  const size_t pieces = size_t(resolve_threads(threads)), n = values.size();
  const auto bound = [&](size_t i) { return values.begin() + std::ptrdiff_t(n * i / pieces); };
  parallel_for(pieces, threads, [&](size_t i) { std::sort(bound(i), bound(i + 1)); });
  for (size_t width = 1; width < pieces; width *= 2)
    for (size_t i = 0; i + width < pieces; i += 2 * width)
      std::inplace_merge(bound(i), bound(i + width), bound(std::min(pieces, i + 2 * width)));
}

// Every undirected edge used by exactly two triangles, once in each direction; no triangle
// repeats a vertex.
bool closed_oriented_manifold(std::span<const Triangle> triangles, int threads) {
  std::vector<uint64_t> directed;
  directed.reserve(3 * triangles.size());
  for (const auto& tri : triangles)
    for (int e = 0; e < 3; ++e) {
      const uint32_t a = tri[size_t(e)], b = tri[size_t((e + 1) % 3)];
      if (a == b) return false;
      directed.push_back((uint64_t{a} << 32) | b);
    }
  parallel_sort(directed, threads);
  if (std::adjacent_find(directed.begin(), directed.end()) != directed.end()) return false;
  const bool paired = all_of_parallel(directed.size(), threads, [&](size_t i) {
    const uint64_t e = directed[i];
    return std::binary_search(directed.begin(), directed.end(), (e << 32) | (e >> 32));
  });
  return paired && !directed.empty();
}

double det(const Vec& a, const Vec& b, const Vec& c) { return a.dot(b.cross(c)); }

// Connected components of the triangles (through shared vertices): the component of each vertex
// that a triangle uses, -1 for an unused vertex; returns the number of components.
uint32_t components(const FlightplanMesh& mesh, std::span<const Triangle> triangles,
                    std::vector<int32_t>& component) {
  std::vector<uint32_t> parent(mesh.vertex_count);
  std::iota(parent.begin(), parent.end(), 0u);
  const auto find = [&](uint32_t v) {
    while (parent[v] != v) v = parent[v] = parent[parent[v]];
    return v;
  };
  for (const auto& tri : triangles)
    for (int k = 1; k < 3; ++k) parent[find(tri[size_t(k)])] = find(tri[0]);
  component.assign(mesh.vertex_count, -1);
  std::vector<int32_t> label(mesh.vertex_count, -1);
  uint32_t count = 0;
  for (const auto& tri : triangles)
    for (uint32_t v : tri) {
      const uint32_t root = find(v);
      if (label[root] < 0) label[root] = int32_t(count++);
      component[v] = label[root];
    }
  return count;
}

// The triangles with every vertex replaced by the first vertex at the same position at every
// key: loaders split vertices along seams of normals and texture coordinates, and such copies
// move together (the same arithmetic on the same keys), so the welded mesh is the same surface.
// A triangle left with a repeated vertex is a segment at every instant (the poles of a UV
// sphere): it covers no pixel, Embree never hits it, and it leaves out an edge in both
// directions, so it is dropped.
std::vector<Triangle> welded(const FlightplanMesh& mesh, size_t keys) {
  std::vector<uint32_t> order(mesh.vertex_count);
  std::iota(order.begin(), order.end(), 0u);
  const auto less = [&](uint32_t a, uint32_t b) {
    for (size_t k = 0; k < keys; ++k) {
      const Vec &p = mesh.key_position(k, a), &q = mesh.key_position(k, b);
      for (int i = 0; i < 3; ++i)
        if (p[i] != q[i]) return p[i] < q[i];
    }
    return a < b;
  };
  std::sort(order.begin(), order.end(), less);
  const auto same = [&](uint32_t a, uint32_t b) {
    for (size_t k = 0; k < keys; ++k)
      if (mesh.key_position(k, a) != mesh.key_position(k, b)) return false;
    return true;
  };
  std::vector<uint32_t> canonical(mesh.vertex_count);
  for (size_t i = 0; i < order.size(); ++i)
    canonical[order[i]] = i > 0 && same(order[i - 1], order[i]) ? canonical[order[i - 1]] : order[i];
  std::vector<Triangle> out;
  out.reserve(mesh.triangles.size());
  for (const auto& tri : mesh.triangles) {
    const Triangle w = {canonical[tri[0]], canonical[tri[1]], canonical[tri[2]]};
    if (w[0] != w[1] && w[1] != w[2] && w[2] != w[0]) out.push_back(w);
  }
  return out;
}

// c at each key: the centroid of each component's vertices (unused vertices do not count), at
// [key * count + component].
std::vector<Vec> component_centres(const FlightplanMesh& mesh, const std::vector<int32_t>& component, uint32_t count,
                                   size_t keys, int threads) {
  std::vector<uint32_t> members(count, 0);
  for (uint32_t v = 0; v < mesh.vertex_count; ++v)
    if (component[v] >= 0) ++members[size_t(component[v])];
  std::vector<Vec> centre(keys * count, Vec::Zero());
  parallel_for(keys, threads, [&](size_t k) {
    for (uint32_t v = 0; v < mesh.vertex_count; ++v)
      if (component[v] >= 0) centre[k * count + size_t(component[v])] += mesh.key_position(k, v);
    for (uint32_t i = 0; i < count; ++i) centre[k * count + i] /= double(members[i]);
  });
  return centre;
}

// (2) on every segment [key k0, key k1] (one constant "segment" for a standing mesh): the
// cubic det(v0 - c, v1 - c, v2 - c) in the local time u in [0, 1]. Each v_i - c is
// (1 - u) P_i + u Q_i, and det is trilinear, so its k-th Bernstein coefficient is the mean of
// the determinants taking Q in k of the three places and P in the others. Each block of
// triangles proves one sign over all segments (0: none), then the blocks must agree.
int proved_orientation(const FlightplanMesh& mesh, std::span<const Triangle> triangles,
                       const std::vector<int32_t>& component, const std::vector<Vec>& centre, uint32_t count,
                       size_t keys, int threads, WorkProgress* progress) {
  std::vector<int> block_sign(block_count(triangles.size()), 0);
  const size_t segments = culling_proof_segments(mesh);
  parallel_for_dynamic(block_sign.size(), threads, [&](size_t block) {
    int sigma = 0;
    const size_t end = std::min(triangles.size(), (block + 1) * kBlock);
    if (progress != nullptr) progress->add((end - block * kBlock) * segments);
    for (size_t t = block * kBlock; t < end; ++t) {
      const Triangle& tri = triangles[t];
      const size_t comp = size_t(component[tri[0]]);
      // The end of one segment starts the next: each key's offsets and lengths are found once.
      std::array<Vec, 3> p, q;
      std::array<double, 3> p_norm, q_norm;
      for (int i = 0; i < 3; ++i) {
        q[size_t(i)] = mesh.key_position(0, tri[size_t(i)]) - centre[comp];
        q_norm[size_t(i)] = q[size_t(i)].norm();
      }
      for (size_t k1 = keys > 1 ? 1 : 0; k1 < keys; ++k1) {
        p = q;
        p_norm = q_norm;
        double bound = 1;
        for (int i = 0; i < 3; ++i) {
          q[size_t(i)] = mesh.key_position(k1, tri[size_t(i)]) - centre[k1 * count + comp];
          q_norm[size_t(i)] = q[size_t(i)].norm();
          bound *= std::max(p_norm[size_t(i)], q_norm[size_t(i)]);
        }
        const std::array<double, 4> b = {
            det(p[0], p[1], p[2]),
            (det(q[0], p[1], p[2]) + det(p[0], q[1], p[2]) + det(p[0], p[1], q[2])) / 3,
            (det(p[0], q[1], q[2]) + det(q[0], p[1], q[2]) + det(q[0], q[1], p[2])) / 3,
            det(q[0], q[1], q[2])};
        const int sign = cubic_sign_on_unit_interval(b, kRelativeMargin * bound, kSubdivisionDepth);
        if (sign == 0 || (sigma != 0 && sign != sigma)) {
          block_sign[block] = 0;
          return;
        }
        sigma = sign;
      }
    }
    block_sign[block] = sigma;
  });
  const int sigma = block_sign.empty() ? 0 : block_sign[0];
  if (sigma == 0 || std::any_of(block_sign.begin(), block_sign.end(), [&](int s) { return s != sigma; }))
    return 0;
  return sigma;
}

// (3) at key 0: the angle each triangle spans at its vertex a, about the axis a - c, between
// the directions to its two other vertices (in (0, pi) by (2)); summed per vertex, in triangle
// order (the sums are the same whatever the threads). True when every used vertex turns by at
// least 3 pi.
bool vertex_turns_hold(const FlightplanMesh& mesh, std::span<const Triangle> triangles,
                       const std::vector<int32_t>& component, const std::vector<Vec>& centre, int sigma,
                       int threads) {
  std::vector<std::array<double, 3>> angle(triangles.size());
  parallel_for(triangles.size(), threads, [&](size_t t) {
    const Triangle& tri = triangles[t];
    const Vec& c = centre[size_t(component[tri[0]])];
    for (int i = 0; i < 3; ++i) {
      const Vec axis = mesh.key_position(0, tri[size_t(i)]) - c;
      const Vec x = mesh.key_position(0, tri[size_t((i + 1) % 3)]) - c;
      const Vec y = mesh.key_position(0, tri[size_t((i + 2) % 3)]) - c;
      const double axis2 = axis.squaredNorm();
      const Vec xp = x - (x.dot(axis) / axis2) * axis, yp = y - (y.dot(axis) / axis2) * axis;
      angle[t][size_t(i)] = std::atan2(double(sigma) * det(axis, x, y) / std::sqrt(axis2), xp.dot(yp));
    }
  });
  std::vector<double> turn(mesh.vertex_count, 0.0);
  for (size_t t = 0; t < triangles.size(); ++t)
    for (int i = 0; i < 3; ++i) turn[triangles[t][size_t(i)]] += angle[t][size_t(i)];
  for (uint32_t v = 0; v < mesh.vertex_count; ++v)
    if (component[v] >= 0 && !(turn[v] < 3 * std::numbers::pi)) return false;
  return true;
}

// (4) positions are linear on a segment, so the box of a component at its two end keys holds
// the component throughout it; before the first and after the last key it stands still. True
// when the eye is outside every component's box on every segment.
bool eye_outside_components(const FlightplanMesh& mesh, const std::vector<int32_t>& component, uint32_t count,
                            size_t keys, int threads) {
  std::vector<char> eye_outside(keys, 0);
  parallel_for(keys, threads, [&](size_t k) {
    std::vector<Eigen::AlignedBox3d> boxes(count);
    for (size_t kk = k; kk < std::min(k + 2, keys); ++kk)
      for (uint32_t v = 0; v < mesh.vertex_count; ++v)
        if (component[v] >= 0) boxes[size_t(component[v])].extend(mesh.key_position(kk, v));
    // A closed box: the eye on it declines.
    eye_outside[k] = std::none_of(boxes.begin(), boxes.end(), [](const auto& box) { return box.contains(Vec::Zero()); });
  });
  return std::find(eye_outside.begin(), eye_outside.end(), 0) == eye_outside.end();
}

}  // namespace


int cubic_sign_on_unit_interval(const std::array<double, 4>& b, double margin, int depth) {
  const auto sign_beyond_margin = [margin](double x) { return x > margin ? 1 : x < -margin ? -1 : 0; };
  // The end values are b[0] and b[3]: when they do not share a proved sign, nothing will.
  const int sign = sign_beyond_margin(b[0]);
  if (sign == 0 || sign_beyond_margin(b[3]) != sign) return 0;
  if (sign_beyond_margin(b[1]) == sign && sign_beyond_margin(b[2]) == sign) return sign;
  if (depth == 0) return 0;
  BernsteinPolynomial f;
  f.degree = 3;
  std::copy(b.begin(), b.end(), f.b.begin());
  const auto [left, right] = subdivide(f, 0.5);
  const std::array<double, 4> l = {left.b[0], left.b[1], left.b[2], left.b[3]};
  const std::array<double, 4> r = {right.b[0], right.b[1], right.b[2], right.b[3]};
  const int a = cubic_sign_on_unit_interval(l, margin, depth - 1);
  return a != 0 && cubic_sign_on_unit_interval(r, margin, depth - 1) == a ? a : 0;
}

int back_face_cull_sign(const FlightplanMesh& mesh, int threads, WorkProgress* progress) {
  const size_t keys = mesh.is_static ? 1 : mesh.key_count();
  const std::vector<Triangle> triangles = welded(mesh, keys);
  if (!closed_oriented_manifold(triangles, threads)) return 0;
  std::vector<int32_t> component;
  const uint32_t count = components(mesh, triangles, component);
  const std::vector<Vec> centre = component_centres(mesh, component, count, keys, threads);
  const int sigma = proved_orientation(mesh, triangles, component, centre, count, keys, threads, progress);
  if (sigma == 0) return 0;
  if (!vertex_turns_hold(mesh, triangles, component, centre, sigma, threads)) return 0;
  if (!eye_outside_components(mesh, component, count, keys, threads)) return 0;
  // sigma > 0: outward normals, and a triangle faces the eye at the origin iff
  // ((v1 - v0) x (v2 - v0)) . (0 - v0) > 0, i.e. det(v0, v1, v2) < 0.
  return -sigma;
}

}  // namespace kinray
