#pragma once
// Contacts of a scene's objects over a time window, in time order: the scene's flightplans cut
// into the segments on which every vertex moves linearly, and a contact finder (the kinetic
// separation list, swept volumes or brute force, kinetic/collision/) run on every object pair
// (and, with self, every object alone).
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "kinetic/collision/ksl_stats.h"
#include "kinetic/collision/mesh_contacts.h"
#include "kinetic/tree/tree_stats.h"
#include "scenes/scene.h"

namespace kinray {

enum class ContactStructure { ksl, swept, brute };

struct CollideParams {
  ContactStructure structure = ContactStructure::ksl;
  bool self = false;                   ///< also contacts of each object with itself
  std::vector<std::uint32_t> objects;  ///< the objects to test; empty: all
  double time_begin = -kInfinity, time_end = kInfinity;  ///< clipped to the shot
  /// Collision checks per flightplan segment (interpolated frames): swept volumes run once per
  /// check interval; the kinetic separation list is asked for its contacts at each check time.
  int checks = 1;
  bool audit = false;  ///< the kinetic separation list and its trees audit themselves
};

/// What the kinetic separation list did (structure ksl).
struct KslReport {
  KslStats list;
  TreeStats trees;
  double pad = 0;  ///< the boxes' margin
};

struct SceneContacts {
  std::vector<Contact> contacts;  ///< time order
  ContactCounters counters;
  std::size_t segments = 0;  ///< flightplan segments of the window
  double seconds = 0;        ///< time spent finding the contacts
  std::optional<KslReport> ksl;
};

/// Every contact of the selected objects in the window. Throws InputError for an object index
/// out of range.
[[nodiscard]] SceneContacts find_scene_contacts(const Scene& scene, const CollideParams& params);

/// "ksl", "swept" or "brute"; throws InputError naming --structure otherwise.
[[nodiscard]] ContactStructure parse_contact_structure(const std::string& text);
[[nodiscard]] const char* contact_structure_name(ContactStructure structure);

}  // namespace kinray
