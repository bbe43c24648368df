#include "kinetic/tree/tree_meshes.h"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "kinetic/core/certificate_time.h"
#include "kinetic/core/root_finding.h"

namespace kinray {

double LinearCertificate::failure_time_slow(double now) const {
  Polynomial f;
  f.degree = 1;
  f.c[0] = c0;
  f.c[1] = c1;
  return certificate_failure_time(f, origin, now, end);
}

TreeMeshes::TreeMeshes(std::vector<FlightplanMesh> meshes, double t) : m_meshes(std::move(meshes)) {
  const size_t n = m_meshes.size();
  m_triangle_begin.assign(n + 1, 0);
  m_vertex_begin.assign(n + 1, 0);
  uint64_t triangles = 0, vertices = 0;
  for (size_t m = 0; m < n; ++m) {
    validate_mesh(m_meshes[m], "kinetic tree mesh " + std::to_string(m) + ": ");
    for (const Eigen::Vector3d& p : m_meshes[m].positions) {
      m_scale = std::max(m_scale, p.cwiseAbs().maxCoeff());
      m_shot_lo = m_shot_lo.cwiseMin(p);
      m_shot_hi = m_shot_hi.cwiseMax(p);
    }
    triangles += m_meshes[m].triangles.size();
    vertices += m_meshes[m].vertex_count;
    if (triangles >= (uint64_t{1} << 30) || vertices >= (uint64_t{1} << 31))
      throw std::invalid_argument("kinetic tree: more than 2^30 triangles or 2^31 vertices");
    m_triangle_begin[m + 1] = uint32_t(triangles);
    m_vertex_begin[m + 1] = uint32_t(vertices);
  }
  m_triangle_mesh.resize(triangles);
  m_vertex_mesh.resize(vertices);
  m_triangle_vertices.resize(triangles);
  for (uint32_t m = 0; m < n; ++m) {
    std::fill(m_vertex_mesh.begin() + m_vertex_begin[m],
              m_vertex_mesh.begin() + m_vertex_begin[m + 1], m);
    const auto& tris = m_meshes[m].triangles;
    for (size_t k = 0; k < tris.size(); ++k) {
      const size_t g = m_triangle_begin[m] + k;
      m_triangle_mesh[g] = m;
      for (int c = 0; c < 3; ++c)
        m_triangle_vertices[g][size_t(c)] = m_vertex_begin[m] + tris[k][size_t(c)];
    }
  }
  m_a.resize(vertices);
  m_b.resize(vertices);
  m_end.resize(vertices);
  m_origin.assign(n, 0);
  m_segment_end.assign(n, kInfinityTime);
  m_present.assign(n, 0);
  m_still.assign(n, 1);
  for (uint32_t m = 0; m < n; ++m) set_time(m, t);
}

void TreeMeshes::set_time(uint32_t m, double t) {
  const FlightplanMesh& mesh = m_meshes[m];
  const auto keys = mesh.key_times;
  const size_t n = keys.size();
  // The segment index is the number of keys <= t (GridScene::segment_at): 0 and n stand still.
  const size_t index =
      mesh.is_static ? n : size_t(std::upper_bound(keys.begin(), keys.end(), t) - keys.begin());
  m_origin[m] = keys[index == 0 ? 0 : index - 1];
  m_segment_end[m] = index < n ? keys[index] : kInfinityTime;
  m_still[m] = index == 0 || index >= n;
  m_present[m] = mesh.present(t);
  for (uint32_t local = 0; local < mesh.vertex_count; ++local) {
    const uint32_t v = m_vertex_begin[m] + local;
    if (m_still[m]) {
      m_a[v] = mesh.key_position(index == 0 ? 0 : n - 1, local);
      m_b[v].setZero();
      m_end[v] = m_a[v];
    } else {
      m_a[v] = mesh.key_position(index - 1, local);
      m_end[v] = mesh.key_position(index, local);
      m_b[v] = (m_end[v] - m_a[v]) / (keys[index] - keys[index - 1]);
    }
  }
}

double TreeMeshes::next_change(uint32_t m, double t) const {
  const FlightplanMesh& mesh = m_meshes[m];
  double next = mesh.is_static ? kInfinityTime : m_segment_end[m];
  if (mesh.appear > t) next = std::min(next, mesh.appear);
  if (mesh.disappear > t) next = std::min(next, mesh.disappear);
  return next;
}

bool TreeMeshes::tied_at_both_keys(uint32_t r, uint32_t q, int axis) const {
  const uint32_t m = m_vertex_mesh[r];
  if (m_vertex_mesh[q] != m || m_still[m]) return false;
  return m_a[r][axis] == m_a[q][axis] && m_end[r][axis] == m_end[q][axis];
}

LinearCertificate TreeMeshes::beyond(uint32_t r, uint32_t q, int axis, int sign) const {
  const bool swap = q < r;
  const uint32_t lo = swap ? q : r, hi = swap ? r : q;
  const uint32_t mlo = m_vertex_mesh[lo], mhi = m_vertex_mesh[hi];
  LinearCertificate c;
  c.origin = m_origin[mlo];
  c.end = std::min(m_segment_end[mlo], m_segment_end[mhi]);
  // x_lo - x_hi in lo's local time; within one mesh the origins agree and hi's shift is exactly 0.
  const double hi_at_origin =
      mlo == mhi ? m_a[hi][axis] : m_a[hi][axis] + m_b[hi][axis] * (c.origin - m_origin[mhi]);
  c.c0 = m_a[lo][axis] - hi_at_origin;
  c.c1 = m_b[lo][axis] - m_b[hi][axis];
  if (swap != (sign < 0)) {  // the exact negation for the other order or the min side
    c.c0 = -c.c0;
    c.c1 = -c.c1;
  }
  return c;
}

void TreeMeshes::blends_at(double t, std::vector<FlightplanMesh::KeyBlend>& out) const {
  out.resize(m_meshes.size());
  for (size_t m = 0; m < m_meshes.size(); ++m) out[m] = m_meshes[m].blend_at(t);
}

}  // namespace kinray
