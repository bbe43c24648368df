#pragma once
// Contacts of a scene's objects over a time window, in time order: the scene's flightplans cut
// into the segments on which every vertex moves linearly, and a contact finder (swept volumes or
// brute force, kinetic/collision/) run on every object pair (and, with self, every object alone).
#include <cstdint>
#include <string>
#include <vector>

#include "kinetic/collision/mesh_contacts.h"
#include "scenes/scene.h"

namespace kinray {

enum class ContactStructure { swept, brute };

struct CollideParams {
  ContactStructure structure = ContactStructure::swept;
  bool self = false;                   ///< also contacts of each object with itself
  std::vector<std::uint32_t> objects;  ///< the objects to test; empty: all
  double time_begin = -kInfinity, time_end = kInfinity;  ///< clipped to the shot
};

struct SceneContacts {
  std::vector<Contact> contacts;  ///< time order
  ContactCounters counters;
  std::size_t segments = 0;  ///< flightplan segments of the window
  double seconds = 0;        ///< time spent finding the contacts
};

/// Every contact of the selected objects in the window. Throws InputError for an object index
/// out of range.
[[nodiscard]] SceneContacts find_scene_contacts(const Scene& scene, const CollideParams& params);

/// "swept" or "brute"; throws InputError naming --structure otherwise.
[[nodiscard]] ContactStructure parse_contact_structure(const std::string& text);

}  // namespace kinray
