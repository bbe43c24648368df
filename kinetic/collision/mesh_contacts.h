#pragma once
// Contacts between and within deforming triangle meshes over one flightplan segment, on which
// every vertex moves linearly: the triangle-pair level shared by every contact finder (brute
// force, swept volumes, and the kinetic separation list), so that all of them run the same
// primitive tests per triangle pair and report contacts the same way.
#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "kinetic/collision/contact_pair.h"
#include "kinetic/collision/primitive_ccd.h"
#include "kinetic/collision/primitive_owners.h"

namespace kinray {

/// One object over one segment [time_begin, time_end]: its triangles (vertex indices in the
/// object's own numbering) and every vertex's position at both ends. With the triangles around
/// each vertex, a primitive pair is tested by its owner triangle pair alone (primitive_owners.h);
/// without, by every triangle pair that meets it. Two sides with the same `object` are the
/// object against itself. (Not `MeshSegment`: that is the grid's record of which segment a mesh
/// is on, and two classes of one name in one namespace break the one-definition rule.)
struct MeshSweep {
  std::uint32_t object = 0;
  std::span<const std::array<std::uint32_t, 3>> triangles;
  std::span<const Eigen::Vector3d> start, end;
  const VertexTriangles* around = nullptr;
};

/// A time of contact between two primitives.
struct Contact {
  double time = 0;  ///< global time (a lower bound, see kContactTimeEarliness, scaled)
  ContactType type = ContactType::vertex_face;
  std::array<std::uint32_t, 2> objects{};  ///< of the first and of the second primitive
  /// vf: the vertex, then the face's three; ee: edge a's two, then edge b's two (object numbering)
  std::array<std::uint32_t, 4> vertices{};
  Eigen::Vector3d point = Eigen::Vector3d::Zero();  ///< where they touch at `time`

  friend bool operator<(const Contact& a, const Contact& b);
  friend bool operator==(const Contact& a, const Contact& b);  ///< all but `point`
};

/// What a contact finder did (for --stats).
struct ContactCounters {
  std::uint64_t segments = 0;        ///< (object pair, flightplan segment) pairs examined
  std::uint64_t triangle_pairs = 0;  ///< pairs handed to the primitive tests
  std::uint64_t node_visits = 0;     ///< bounding volume tests (swept volumes)
  PrimitiveCcdCounters primitives;

  ContactCounters& operator+=(const ContactCounters& o);
};

/// Triangles of one mesh that share a vertex (or an edge) touch by construction, not contacts.
[[nodiscard]] bool triangles_adjacent(const std::array<std::uint32_t, 3>& a,
                                      const std::array<std::uint32_t, 3>& b);

/// The 15 primitive tests of triangle ta of `a` against triangle tb of `b` (6 vertex-face, 9
/// edge-edge), those the pair owns when the segments carry the triangles around their vertices
/// (primitive_owners.h), on the segment [time_begin, time_end]; appends every contact (those in `window`
/// of the segment's local time, at the times the whole segment's tests give them), named one
/// way (an edge-edge contact: each edge's smaller vertex id first, then the edge pair in
/// (object, vertices) order), so that the same primitive pair met from two triangle pairs, or
/// from either side, gives identical contacts, points included.
void triangle_pair_contacts(const MeshSweep& a, std::uint32_t ta, const MeshSweep& b,
                            std::uint32_t tb, double time_begin, double time_end,
                            std::vector<Contact>& out, PrimitiveCcdCounters& counters,
                            LocalWindow window = {});
/// The same tests restricted to `owned` (owned_primitives' bits, whatever the segments carry):
/// for a caller that keeps the pair's owners from one segment to the next.
void triangle_pair_contacts(const MeshSweep& a, std::uint32_t ta, const MeshSweep& b,
                            std::uint32_t tb, double time_begin, double time_end,
                            std::vector<Contact>& out, PrimitiveCcdCounters& counters,
                            LocalWindow window, OwnedPrimitives owned);
/// The primitive pairs triangle_pair_contacts tests for (ta, tb): the owned ones when both
/// segments carry the triangles around their vertices, else all fifteen.
[[nodiscard]] OwnedPrimitives tested_primitives(const MeshSweep& a, std::uint32_t ta,
                                                const MeshSweep& b, std::uint32_t tb);

/// Sorts contacts in time order and removes the repeats that arise when a vertex or an edge
/// belongs to several tested triangle pairs.
void sort_contacts(std::vector<Contact>& contacts);

/// Brute force: every triangle pair of a and b (or, when &a == &b, every non-adjacent pair of a
/// with itself).
void brute_force_contacts(const MeshSweep& a, const MeshSweep& b, double time_begin,
                          double time_end, std::vector<Contact>& out, ContactCounters& counters);

}  // namespace kinray
