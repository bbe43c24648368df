#pragma once
// The kinetic separation list of Zachmann and Weller (VRIPHYS 2006; docs/design.md, "Kinetic
// separation list"): continuous collision detection between two kinetic AABB trees, or one tree
// against itself, as the maintenance of the front of their bounding volume test tree (BVTT).
//
// Every node pair met by the simultaneous traversal is a record:
//   - separated: some axis separates the two boxes by more than the pad; its witness is one
//     linear certificate between two realizers (the lower box's max, the upper box's min);
//   - an overlapping leaf pair: a triangle pair, listed, tested by the primitive CCD over the
//     part of each flightplan segment during which it is listed (its overlap episodes);
//   - expanded: an overlapping inner pair whose children pairs are records; it is watched for
//     separation (six linear certificates, one per axis and direction).
// The separation list is the front: the separated pairs and the overlapping leaf pairs. Events:
// a witness fails (another axis takes over, or the pair overlaps and is replaced by its children
// pairs); a watched pair separates (its children pairs are replaced by the pair); a realizer of a
// node in a record changes (KineticBvh's observer: the record is recertified); a segment begins
// (every record is recertified). A listed leaf pair is tested from the time it is listed to its
// separation event (or the segment's end), and again from there whenever that event moves later.
//
// Lazy trees (KineticBvh::Config::lazy, as KineticContactFinder builds them): at each key a pair
// whose two segment boxes (every key position of the segment below each node) are apart by more
// than twice the pad is separated through the segment without a certificate (apart), and its nodes
// are not read; the list reads, and so wakes, only the subtrees of its other pairs. An expanded
// pair met at a key with a sleeping node is kept expanded to the next key, unwatched (its children
// pairs hold the front there), rather than waking its subtrees to watch it.
//
// Conservative: boxes are closed and padded by `pad`, far above the rounding between the trees'
// motion a + b (t - o) and the primitive tests' segment motion; a triangle pair in contact at t*
// is listed at t*, so the contacts are exactly the brute force's on the same segments.
// Self (one tree): a node paired with itself always overlaps and is never listed; its children
// pairs are (l, l), (l, r), (r, r). Triangles sharing a vertex are never paired.
#include <array>
#include <cstdint>
#include <set>
#include <vector>

#include "kinetic/collision/ksl_stats.h"
#include "kinetic/collision/mesh_contacts.h"
#include "kinetic/collision/tested_windows.h"
#include "kinetic/core/simulator.h"
#include "kinetic/tree/kinetic_bvh.h"

namespace kinray {

/// A pair of the front: node a of the first tree, node b of the second.
struct KslPair {
  uint32_t a = 0, b = 0;
  bool overlapping = false;  ///< an overlapping leaf pair (else separated)
  friend auto operator<=>(const KslPair&, const KslPair&) = default;
};

class KineticSeparationList {
 public:
  /// Over trees a and b (&a == &b: self-collision), both at the same time and advanced by the
  /// caller in time order with this list (KineticContactFinder). `pad`: the boxes' margin.
  /// Registers a realizer observer with the trees: the list must outlive their advances.
  KineticSeparationList(KineticBvh& a, KineticBvh& b, double pad);
  KineticSeparationList(const KineticSeparationList&) = delete;
  KineticSeparationList& operator=(const KineticSeparationList&) = delete;

  /// A flightplan segment [time_begin, time_end] begins (the trees are at time_begin): the meshes'
  /// positions at both ends, as every contact finder tests them. The first call traverses.
  void begin_segment(const MeshSweep& a, const MeshSweep& b, double time_begin,
                     double time_end);
  /// Handles the trees' realizer changes reported since the last call and every event up to t.
  void advance_to(double t);
  [[nodiscard]] double now() const { return m_sim.now(); }
  [[nodiscard]] double next_event_time() const { return m_sim.next_event_time(); }

  /// Moves the contacts no later contact can precede into `out`, in time order: those found so
  /// far with time <= t - (twice the primitive earliness bound of the segment); all with t = inf.
  void release_contacts(double t, std::vector<Contact>& out);

  /// At t strictly between events and within the segment: the list equals a fresh traversal's
  /// front at t, every certificate holds at t, every event is at its certificate's failure time,
  /// every listed leaf pair was tested on this segment from now to its separation event (or the
  /// segment's end). Throws KineticAuditFailure with context.
  void audit(double t) const;

  /// The front now, sorted.
  [[nodiscard]] std::vector<KslPair> front() const;
  /// A fresh simultaneous traversal's front at t, sorted (what audit compares with).
  [[nodiscard]] std::vector<KslPair> traversal_front(double t) const;

  [[nodiscard]] KslStats stats() const;
  [[nodiscard]] const ContactCounters& counters() const { return m_counters; }

 private:
  /// Tests corrupt a list's records through this to see the audit report it.
  friend struct KineticSeparationListTestAccess;
  static constexpr uint32_t kNone = ~0u;
  /// apart: separated through the segment by the segment boxes (no certificate, no event);
  /// unwatched: expanded, not watched until the next key (lazy trees).
  enum class State : uint8_t { none, separated, leaf, expanded, apart, unwatched };
  struct Record {
    uint32_t a = 0, b = 0;
    uint32_t parent = kNone;
    std::array<uint32_t, 4> children{kNone, kNone, kNone, kNone};
    uint8_t child_count = 0;
    State state = State::none;
    uint8_t witness = 0;     ///< separated: d = 2 axis + (0: a below b, 1: b below a)
    bool permanent = false;  ///< self: a node with itself, always overlapping
    bool alive = false, dirty = false;
    EventHandle event = kNoEvent;
    std::array<uint32_t, 2> next{kNone, kNone}, prev{kNone, kNone};  ///< node lists of a, b
    /// A leaf pair: the primitive pairs its triangle pair tests (owners depend on the topology
    /// alone), found at its first test and kept while the pair stays listed, over segments.
    OwnedPrimitives owned = kOwnersUnknown;
  };
  static constexpr OwnedPrimitives kOwnersUnknown = 0xFFFF;  ///< no bit 15 among the primitives
  enum class Reason : uint8_t { event, recertification, flightplan };
  enum class Outcome : uint8_t { unchanged, witness_change, overlap, separation };

  [[nodiscard]] const KineticBvh& tree(int which) const { return which == 0 ? m_a : m_b; }
  /// Live certificates of a record in a state.
  [[nodiscard]] static uint64_t live_certificates(State state, bool permanent);
  /// Lazy trees: a direction d (as in gap_certificate) along which the two nodes' segment boxes
  /// are apart by more than twice the pad, or -1.
  [[nodiscard]] int apart_direction(uint32_t a, uint32_t b) const;
  /// Wakes the record's two nodes (lazy trees) before its certificates read their realizers.
  void wake(const Record& r);
  /// Lazy trees: the nodes certifying the pair would wake (its sleeping subtrees).
  [[nodiscard]] uint64_t sleeping_nodes(const Record& r) const;
  /// A pair at a key that would wake more nodes than this is opened instead (unwatched, its
  /// children pairs visited): waking costs each node, opening only the pairs near the passage.
  static constexpr uint64_t kWakeLimit = 1024;
  /// A record at a key, lazy trees: apart, or recertified (an expanded one after its children,
  /// watched only when both its nodes are awake by then).
  void recertify_at_key(uint32_t id);
  /// Side s of a node of tree `which` at t: its realizer's coordinate when awake, else the extreme
  /// of its leaves' vertices (the audit, which must not wake what the list left asleep).
  [[nodiscard]] double side_at(int which, uint32_t node, int s, double t) const;
  [[nodiscard]] static uint32_t node(const Record& r, int which) { return which == 0 ? r.a : r.b; }
  /// gap_d - pad > 0 as a linear certificate: d = 2 axis + lower, the upper box's min minus the
  /// lower box's max (lower 0: a's box is below b's). Its origin is the segment's beginning, so
  /// that a certificate has the same coefficients whenever it is computed in the segment.
  [[nodiscard]] LinearCertificate gap_certificate(const Record& r, int d) const;
  [[nodiscard]] LinearCertificate gap_certificate(uint32_t a, uint32_t b, int d,
                                                  double origin) const;
  /// The six gap certificates of a record, gaps[d] == gap_certificate(r, d): each of the two
  /// nodes' twelve realizers is met once, and an event that needs the six twice (a witness that
  /// fails into an overlap, which is then watched; a watched pair that separates, which then
  /// needs a witness) computes them once.
  using Gaps = std::array<LinearCertificate, 6>;
  void gap_certificates(const Record& r, Gaps& gaps);
  /// The separating direction that holds longest just after now (its failure time), or -1.
  [[nodiscard]] int find_witness(const Gaps& gaps, double& failure) const;

  uint32_t create(uint32_t a, uint32_t b, uint32_t parent);
  void destroy_children(uint32_t id);
  void link(uint32_t id);
  void unlink(uint32_t id);
  void set_state(uint32_t id, State state);
  /// A new record: separated with a witness, or overlapping (expanded, or a listed leaf pair).
  void classify_new(uint32_t id);
  /// `gaps`: the record's, none of which separates just after now (nullptr for a permanent
  /// record, which is never watched).
  void overlap(uint32_t id, const Gaps& gaps);
  void expand(uint32_t id, const Gaps* gaps);
  void separate(uint32_t id, int witness, double failure);
  /// An overlapping record, `gaps` its six: separates now, or schedules the first separation.
  Outcome watch(uint32_t id, const Gaps& gaps);
  /// The record's state just after now, from its current realizers; schedules its event.
  Outcome certify(uint32_t id);
  void count(Outcome outcome, Reason reason);
  void schedule(uint32_t id, double time);
  /// A listed leaf pair: tests its triangle pair from where its tests so far end (or now) to its
  /// separation event, or the segment's end when it has none in the segment.
  void test_leaf(uint32_t id);
  /// The end of the test window of a listed leaf pair: its event time, at most the segment's end.
  [[nodiscard]] double episode_end(const Record& r) const;
  [[nodiscard]] uint64_t triangle_pair(const Record& r) const;
  [[nodiscard]] bool relevant(const Record& r, int which, int side) const;
  void on_realizer_change(int which, uint32_t node, int side);
  void recertify_dirty();
  [[nodiscard]] bool pairable(uint32_t a, uint32_t b) const;
  /// A node pair's children pairs (at most four), in a fixed array: an overlap allocates none.
  struct Children {
    std::array<std::pair<uint32_t, uint32_t>, 4> pairs;
    int count = 0;
    [[nodiscard]] auto begin() const { return pairs.begin(); }
    [[nodiscard]] auto end() const { return pairs.begin() + count; }
  };
  [[nodiscard]] Children children_of(uint32_t a, uint32_t b) const;
  [[nodiscard]] bool separated_at(uint32_t a, uint32_t b, double t) const;
  /// The record of the node pair in state `state`, if there is one (the audit).
  [[nodiscard]] bool has_record(uint32_t a, uint32_t b, State state) const;
  void traverse(uint32_t a, uint32_t b, double t, std::vector<KslPair>& out) const;
  void audit_record(uint32_t id, double t) const;

  KineticBvh& m_a;
  KineticBvh& m_b;
  bool m_self = false;
  bool m_lazy = false;  ///< both trees lazy
  double m_pad = 0;
  Simulator m_sim;
  std::vector<Record> m_records;
  std::vector<uint32_t> m_free;
  uint32_t m_root = kNone;
  std::array<std::vector<uint32_t>, 2> m_head;  ///< per node of tree a / b: its first record
  std::array<std::vector<uint32_t>, 2> m_subtree_nodes;  ///< per node of tree a / b (lazy trees)
  std::vector<uint32_t> m_dirty;

  const MeshSweep* m_mesh_a = nullptr;
  const MeshSweep* m_mesh_b = nullptr;
  double m_segment_begin = 0, m_segment_end = 0;
  /// Per triangle pair tested on this segment: the (global) time up to which it was tested.
  TestedWindows m_tested_until;
  std::set<Contact> m_found;       ///< contacts found on this segment (windows share their ends)
  std::vector<Contact> m_pending;  ///< a min-heap on Contact's order
  Contact m_last_released;
  bool m_released_any = false;

  KslStats m_stats;
  ContactCounters m_counters;
};

}  // namespace kinray
