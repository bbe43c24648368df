#pragma once
// Continuous collision detection of several deforming meshes by kinetic separation lists: one
// kinetic AABB tree per object, one list per object pair (and per object with itself), all
// advanced together in time order (a tree's realizer changes reach the lists at the time they
// happen). The caller walks the flightplan segments and asks for the contacts up to any times it
// likes; what the structures compute does not depend on how often it asks.
#include <cstdint>
#include <memory>
#include <span>
#include <utility>
#include <vector>

#include "kinetic/collision/kinetic_separation_list.h"
#include "kinetic/collision/mesh_contacts.h"
#include "kinetic/tree/kinetic_bvh.h"

namespace kinray {

class KineticContactFinder {
 public:
  /// meshes[i]: object i's flightplans (its presence is ignored: contacts are found at every
  /// time, as brute force does); pairs (i, j), i == j for self-contacts. Built at time t; with
  /// audit, the trees and the lists audit themselves after every advance. lazy_trees: the trees
  /// compute at a key only the nodes the lists read (KineticBvh::Config::lazy); false: every node
  /// (the same contacts; tests compare the two).
  KineticContactFinder(std::vector<FlightplanMesh> meshes,
                       std::vector<std::pair<uint32_t, uint32_t>> pairs, double t, bool audit,
                       bool lazy_trees = true);

  /// Advances to `begin`, then begins the segment [begin, end]: segments[i] holds object i's
  /// positions at both ends (kept alive by the caller until the next segment begins).
  void begin_segment(std::span<const MeshSweep> segments, double begin, double end);
  /// Advances to t (within the segment) and appends the contacts released so far, in time order.
  void advance_to(double t, std::vector<Contact>& out);
  /// Appends every contact not yet released (at the end of the window).
  void finish(std::vector<Contact>& out);

  /// The lists' counters, summed.
  [[nodiscard]] KslStats stats() const;
  /// The trees' counters, summed.
  [[nodiscard]] TreeStats tree_stats() const;
  [[nodiscard]] ContactCounters counters() const;
  [[nodiscard]] double pad() const { return m_pad; }

  /// The boxes' margin: 1e-12 of the largest coordinate (the rounding between a tree's motion
  /// a + b (t - o) and a segment's interpolated positions) plus the largest speed times 64 ulps of
  /// the largest time (the rounding of t - o and of interpolation weights).
  [[nodiscard]] static double contact_pad(std::span<const FlightplanMesh> meshes, double t_end);

 private:
  /// Processes every event of the trees and the lists up to t, in time order.
  void step_to(double t);
  void audit() const;

  std::vector<std::unique_ptr<KineticBvh>> m_trees;  // before the lists: destroyed after them
  std::vector<std::pair<uint32_t, uint32_t>> m_pairs;
  std::vector<std::unique_ptr<KineticSeparationList>> m_lists;
  std::vector<Contact> m_merge;
  double m_pad = 0, m_segment_end = 0;
  bool m_audit = false;
};

}  // namespace kinray
