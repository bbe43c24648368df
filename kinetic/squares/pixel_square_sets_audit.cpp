// The brute-force audit (PixelSquareSets::audit), at a time strictly between events: the queue
// holds nothing due, meshes are on the segment of now, every certificate a record watches has the
// sign the record claims, every record's strips follow from its signs, and every pixel's set is
// exactly the triangles square_overlap finds overlapping its square (ties counted, not failed).
// Nothing here aborts: each problem names the time, the invariant and where.
#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include "kinetic/grid/mesh_segments.h"
#include "kinetic/squares/pixel_square_sets.h"

namespace kinray {

class PixelSquareSets::Audit {
 public:
  Audit(const PixelSquareSets& sets, size_t* ties)
      : m_sets(sets), m_t(sets.now()), m_ties(ties), m_users(sets.m_vertices.size(), 0) {}

  std::vector<std::string> run() && {
    const EventQueue& q = m_sets.m_sim.queue();
    if (!q.empty() && q.top_key().time <= m_t)
      report("queue", "an event at or before now is pending");
    for (uint32_t m = 0; m < m_sets.m_input.meshes.size(); ++m) mesh(m);
    edges();
    pixels();
    return std::move(m_problems);
  }

 private:
  void report(const char* invariant, const std::string& what) {
    if (m_problems.size() >= 20) return;
    char head[96];
    std::snprintf(head, sizeof head, "t = %.17g: %s: ", m_t, invariant);
    m_problems.push_back(head + what);
  }

  void mesh(uint32_t m) {
    const FlightplanMesh& mesh = m_sets.m_input.meshes[m];
    const std::string where = "mesh " + std::to_string(m);
    if (bool(m_sets.m_present[m]) != mesh.present(m_t)) report("mesh presence", where);
    if (!mesh.is_static && mesh_segment_at(mesh, m_t).index != m_sets.m_segments[m].index)
      report("mesh segment", where + " on the wrong key segment");
    for (uint32_t tri = m_sets.m_triangle_begin[m]; tri < m_sets.m_triangle_begin[m + 1]; ++tri)
      record(tri, m_sets.m_present[m] != 0);
    if (m_sets.m_present[m])
      for (uint32_t v = m_sets.m_vertex_begin[m]; v < m_sets.m_vertex_begin[m + 1]; ++v) vertex(v);
  }

  /// Every edge is followed by as many records before the eye as its count says, over the row
  /// lines between its end points' rows, and those records' copies are its steps.
  void edges() {
    const PixelSquareSets& s = m_sets;
    std::vector<uint32_t> users(s.m_edges.size(), 0);
    for (uint32_t tri = 0; tri < s.m_records.size(); ++tri) {
      const TriangleRecord& rec = s.m_records[tri];
      if (rec.mode != TriangleRecord::Mode::kFront) continue;
      for (int e = 0; e < 3; ++e) ++users[s.m_triangle_edges[tri][size_t(e)]];
      for (const EdgeOnLine& line : rec.lines) {
        const EdgeTracker& et = s.m_edges[s.m_triangle_edges[tri][size_t(line.edge)]];
        const int k = line.line - et.line_begin;
        if (k < 0 || k >= int(et.lines.size())) {
          report("edge lines",
                 "triangle " + std::to_string(tri) + " reads a line its edge does not follow");
          continue;
        }
        const CornerStep& own = et.lines[size_t(k)].step;
        if (line.step.count != own.count ||
            line.step.first != s.edge_direction(tri, line.edge) * own.first)
          report("edge copies",
                 "triangle " + std::to_string(tri) + " holds a stale copy of an edge's step");
      }
    }
    for (uint32_t edge = 0; edge < s.m_edges.size(); ++edge) {
      const EdgeTracker& et = s.m_edges[edge];
      const std::string where = "edge " + std::to_string(edge);
      if (et.users != users[edge]) report("edge users", where + " has a wrong count of users");
      if (et.users == 0) {
        if (!et.lines.empty()) report("edge lines", where + " follows lines for nobody");
        continue;
      }
      const int r0 = s.m_vertices[s.m_edge_vertices[edge][0]].cells.row;
      const int r1 = s.m_vertices[s.m_edge_vertices[edge][1]].cells.row;
      const int begin = std::max(std::min(r0, r1) + 1, 0);
      const int end = std::max(std::min(std::max(r0, r1), s.m_lattice.height()) + 1, begin);
      if (et.line_begin != begin || int(et.lines.size()) != end - begin)
        report("edge lines", where + " follows the wrong row lines");
    }
  }

  /// A vertex's claimed side of the eye plane and cells (followed exactly while records read
  /// them, as many as its count of users says) hold.
  void vertex(uint32_t v) {
    const VertexTracker& vt = m_sets.m_vertices[v];
    const std::string where = "vertex " + std::to_string(v);
    if (vt.users != m_users[v]) report("vertex users", where + " has a wrong count of users");
    if ((vt.users > 0) != (vt.cells.row != kNoCell) ||
        (vt.cells.column != kNoCell) != (vt.users > 0 && vt.cells.z_sign > 0))
      report("vertex cells", where + " followed while unused or the other way round");
    const PointMotion p = m_sets.vertex_motion(v);
    const double s = m_t - m_sets.m_segments[m_sets.m_vertex_mesh[v]].origin;
    auto claim_sign = [&](const Polynomial& f, int sign, const char* what) {
      if (sign_plus(f, s) != sign)
        report("certificate", where + " " + what + " has the wrong sign");
    };
    const VertexCells& c = vt.cells;
    claim_sign(Polynomial{p.a.z(), p.b.z()}, c.z_sign, "eye side");
    const SquareLattice& lattice = m_sets.m_lattice;
    auto cell = [&](int axis, int at, int lines, const double* xs, const char* what) {
      if (at == kNoCell) return;
      if (at >= 0) claim_sign(after_line(p, axis, xs[at], c.z_sign), 1, what);
      if (at + 1 < lines) claim_sign(after_line(p, axis, xs[at + 1], c.z_sign), -1, what);
    };
    cell(1, c.row, lattice.height() + 1, lattice.y_lines(), "row cell");
    cell(0, c.column, lattice.width() + 1, lattice.x_lines(), "column cell");
  }

  /// A claimed sign of a certificate: sign_plus of f just after now.
  void claim(const Polynomial& f, int sign, uint32_t tri, const std::string& what) {
    if (sign_plus(f, m_t - m_sets.m_segments[m_sets.m_triangle_mesh[tri]].origin) != sign)
      report("certificate", "triangle " + std::to_string(tri) + " " + what + " has the wrong sign");
  }

  void record(uint32_t tri, bool present) {
    using Mode = TriangleRecord::Mode;
    const TriangleRecord& rec = m_sets.m_records[tri];
    const std::string where = "triangle " + std::to_string(tri);
    if ((rec.mode != Mode::kAbsent) != present) report("record presence", where);
    if (rec.mode == Mode::kAbsent || rec.mode == Mode::kEmpty) return;
    const TriangleMotion tm = m_sets.motion(tri);
    const SquareLattice& lattice = m_sets.m_lattice;
    const std::array<uint32_t, 3> ids = m_sets.vertex_ids(tri);
    int front = 0;
    for (int k = 0; k < 3; ++k) {
      const VertexCells& own = m_sets.m_vertices[ids[size_t(k)]].cells;
      front += own.z_sign > 0;
      if (rec.mode == Mode::kBehind) continue;
      ++m_users[ids[size_t(k)]];
      if (!(rec.vertices[size_t(k)] == own))
        report("record vertices", where + " vertex " + std::to_string(k) + " is not its vertex's");
    }
    const Mode mode = front == 0 ? Mode::kBehind : (front == 3 ? Mode::kFront : Mode::kStraddling);
    if (rec.mode != mode) report("record mode", where + " in the wrong mode for its eye sides");
    if (rec.mode == Mode::kStraddling) {
      claim(tm.orientation(), rec.orientation, tri, "orientation");
      for (int e = 0; e < 3; ++e)
        claim(tm.edge(e).component(0), rec.nx_sign[size_t(e)], tri,
              "edge " + std::to_string(e) + " n_x");
    }
    const int w = lattice.width();
    for (const EdgeOnLine& line : rec.lines) {
      const EdgeNormal n = tm.edge(line.edge);
      const double y = lattice.y_line(line.line);
      const std::string name =
          "edge " + std::to_string(line.edge) + " on row line " + std::to_string(line.line);
      const CornerStep& st = line.step;
      const int last = st.count > w ? w : st.count;
      claim(n.along(lattice.x_line(st.count > w ? 0 : st.count - 1), y), st.first, tri,
            name + " (first corner)");
      claim(n.along(lattice.x_line(last), y), st.count > w ? st.first : -st.first, tri,
            name + " (second corner)");
    }
    for (size_t k = 0; k < rec.strips.size(); ++k) {
      const ColumnRange r = strip_columns(rec, rec.strip_begin + int(k), w);
      if (r.lo != rec.strips[k].lo || r.hi != rec.strips[k].hi)
        report("record strips",
               where + " strip " + std::to_string(rec.strip_begin + int(k)) + " is stale");
    }
  }

  /// Every pixel's set against square_overlap for every present triangle.
  void pixels() {
    const PixelSquareSets& s = m_sets;
    const int w = s.m_lattice.width(), h = s.m_lattice.height();
    std::vector<uint32_t> held(s.m_pixels.size());  // per pixel, how many sightings
    for (uint32_t m = 0; m < s.m_input.meshes.size(); ++m) {
      if (!s.m_present[m]) continue;
      for (uint32_t local = 0; local < s.m_input.meshes[m].triangles.size(); ++local) {
        const std::array<Eigen::Vector3d, 3> p = s.triangle_at(m, local, m_t);
        const SquareTriangle entry{m, local};
        for (int j = 0; j < h; ++j)
          for (int i = 0; i < w; ++i) {
            const std::span<const SquareTriangle> set = s.triangles(i, j);
            const auto n = std::count(set.begin(), set.end(), entry);
            held[size_t(j) * size_t(w) + size_t(i)] += uint32_t(n);
            if (n > 1) report("pixel set", pixel(i, j) + " holds a triangle twice");
            const Overlap truth = square_overlap(p[0], p[1], p[2], s.m_lattice.square(i, j));
            if (truth == Overlap::kTie) {
              if (m_ties != nullptr) ++*m_ties;
            } else if ((truth == Overlap::kYes) != (n > 0)) {
              report("pixel set",
                     pixel(i, j) + " mesh " + std::to_string(m) + " triangle " +
                         std::to_string(local) +
                         (n > 0 ? " held but not overlapping" : " overlapping but not held"));
            }
          }
      }
    }
    for (size_t k = 0; k < held.size(); ++k)
      if (held[k] != s.m_pixels[k].size())
        report("pixel set", "pixel " + std::to_string(k) + " holds a triangle that is not present");
  }

  static std::string pixel(int i, int j) {
    return "pixel (" + std::to_string(i) + ", " + std::to_string(j) + ")";
  }

  const PixelSquareSets& m_sets;
  double m_t;
  size_t* m_ties;
  std::vector<std::string> m_problems;
  std::vector<uint32_t> m_users;  ///< per vertex: the records seen reading its cells
};

std::vector<std::string> PixelSquareSets::audit(size_t* ties) const {
  return Audit(*this, ties).run();
}

}  // namespace kinray
