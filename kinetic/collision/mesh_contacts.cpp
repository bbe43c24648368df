#include "kinetic/collision/mesh_contacts.h"

#include <algorithm>
#include <tuple>

namespace kinray {
namespace {

auto key(const Contact& c) {
  return std::tie(c.time, c.type, c.objects, c.vertices);
}

PrimitiveMotion gather(const MeshSweep& first, std::span<const std::uint32_t> first_vertices,
                       const MeshSweep& second, std::span<const std::uint32_t> second_vertices) {
  PrimitiveMotion m;
  int i = 0;
  for (std::uint32_t v : first_vertices) {
    m.start[i] = first.start[v];
    m.end[i++] = first.end[v];
  }
  for (std::uint32_t v : second_vertices) {
    m.start[i] = second.start[v];
    m.end[i++] = second.end[v];
  }
  return m;
}

/// Names an edge-edge contact one way, each edge's smaller vertex id first, then the edge pair
/// in (object, vertices) order, with `motion`'s points following their vertex ids: an edge shared
/// by two triangles is tested from both, in either direction, and the repeats must be identical,
/// their contact points included (computed from the points in this order).
void name_canonically(Contact& c, PrimitiveMotion& motion) {
  if (c.type != ContactType::edge_edge) return;
  const auto swap_points = [&](int a, int b) {
    std::swap(c.vertices[a], c.vertices[b]);
    std::swap(motion.start[a], motion.start[b]);
    std::swap(motion.end[a], motion.end[b]);
  };
  if (c.vertices[0] > c.vertices[1]) swap_points(0, 1);
  if (c.vertices[2] > c.vertices[3]) swap_points(2, 3);
  if (std::tie(c.objects[0], c.vertices[0], c.vertices[1]) >
      std::tie(c.objects[1], c.vertices[2], c.vertices[3])) {
    std::swap(c.objects[0], c.objects[1]);
    swap_points(0, 2);
    swap_points(1, 3);
  }
}

void test_pair(ContactType type, const MeshSweep& first, std::span<const std::uint32_t> fv,
               const MeshSweep& second, std::span<const std::uint32_t> sv, double time_begin,
               double time_end, std::vector<Contact>& out, PrimitiveCcdCounters& counters,
               LocalWindow window) {
  const PrimitiveMotion motion = gather(first, fv, second, sv);
  const std::vector<double> times = contact_times(type, motion, &counters, window);
  if (times.empty()) return;
  // Named canonically: the contact and its point are then the same whichever triangle pair,
  // and whichever side, meets the primitive pair.
  Contact c;
  c.type = type;
  c.objects = {first.object, second.object};
  int i = 0;
  for (std::uint32_t v : fv) c.vertices[i++] = v;
  for (std::uint32_t v : sv) c.vertices[i++] = v;
  PrimitiveMotion named = motion;
  name_canonically(c, named);
  for (double local : times) {
    c.time = time_begin + local * (time_end - time_begin);
    c.point = contact_point(type, named, local);
    out.push_back(c);
  }
}

}  // namespace

bool operator<(const Contact& a, const Contact& b) {
  return key(a) < key(b);
}
bool operator==(const Contact& a, const Contact& b) {
  return key(a) == key(b);
}

ContactCounters& ContactCounters::operator+=(const ContactCounters& o) {
  segments += o.segments;
  triangle_pairs += o.triangle_pairs;
  node_visits += o.node_visits;
  primitives += o.primitives;
  return *this;
}

bool triangles_adjacent(const std::array<std::uint32_t, 3>& a,
                        const std::array<std::uint32_t, 3>& b) {
  for (std::uint32_t u : a)
    for (std::uint32_t v : b)
      if (u == v) return true;
  return false;
}

OwnedPrimitives tested_primitives(const MeshSweep& a, std::uint32_t ta, const MeshSweep& b,
                                  std::uint32_t tb) {
  if (!a.around || !b.around) return kAllPrimitives;
  return owned_primitives({a.triangles, a.around}, ta, {b.triangles, b.around}, tb,
                          a.object == b.object);
}

void triangle_pair_contacts(const MeshSweep& a, std::uint32_t ta, const MeshSweep& b,
                            std::uint32_t tb, double time_begin, double time_end,
                            std::vector<Contact>& out, PrimitiveCcdCounters& counters,
                            LocalWindow window) {
  triangle_pair_contacts(a, ta, b, tb, time_begin, time_end, out, counters, window,
                         tested_primitives(a, ta, b, tb));
}

void triangle_pair_contacts(const MeshSweep& a, std::uint32_t ta, const MeshSweep& b,
                            std::uint32_t tb, double time_begin, double time_end,
                            std::vector<Contact>& out, PrimitiveCcdCounters& counters,
                            LocalWindow window, OwnedPrimitives owned) {
  const std::array<std::uint32_t, 3>& fa = a.triangles[ta];
  const std::array<std::uint32_t, 3>& fb = b.triangles[tb];
  const auto has = [owned](int bit) { return ((owned >> bit) & 1) != 0; };
  for (int i = 0; i < 3; ++i) {
    if (has(2 * i))
      test_pair(ContactType::vertex_face, a, std::span(&fa[i], 1), b, fb, time_begin, time_end, out,
                counters, window);
    if (has(2 * i + 1))
      test_pair(ContactType::vertex_face, b, std::span(&fb[i], 1), a, fa, time_begin, time_end, out,
                counters, window);
  }
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      if (!has(6 + 3 * i + j)) continue;
      const std::array<std::uint32_t, 2> ea = {fa[i], fa[(i + 1) % 3]};
      const std::array<std::uint32_t, 2> eb = {fb[j], fb[(j + 1) % 3]};
      test_pair(ContactType::edge_edge, a, ea, b, eb, time_begin, time_end, out, counters, window);
    }
}

void sort_contacts(std::vector<Contact>& contacts) {
  std::sort(contacts.begin(), contacts.end());
  contacts.erase(std::unique(contacts.begin(), contacts.end()), contacts.end());
}

void brute_force_contacts(const MeshSweep& a, const MeshSweep& b, double time_begin,
                          double time_end, std::vector<Contact>& out, ContactCounters& counters) {
  const bool self = &a == &b;
  ++counters.segments;
  for (std::uint32_t i = 0; i < a.triangles.size(); ++i)
    for (std::uint32_t j = self ? i + 1 : 0; j < b.triangles.size(); ++j) {
      if (self && triangles_adjacent(a.triangles[i], a.triangles[j])) continue;
      ++counters.triangle_pairs;
      triangle_pair_contacts(a, i, b, j, time_begin, time_end, out, counters.primitives);
    }
}

}  // namespace kinray
