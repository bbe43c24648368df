#pragma once
// Kinetic sorting: the concept the kinetic sorted list, tournament and heap share (KineticSort).
// One idea per header: the keys they sort (sort_keys.h; models in linear_motion_keys.h and
// polynomial_keys.h), their configuration (sort_config.h) and counters (sort_stats.h), and the
// implementation they share (sort_core.h, id_index.h).
//
// Conventions shared by the three structures (see docs/kinetic_core.md, "Kinetic core"):
// - "a before b" holds while the certificate polynomial is > 0; at an instant where it is 0 the
//   sign just after (sign_after) decides; if it is the zero polynomial (identical motions) the
//   smaller id comes first. Exact ties are thus broken by id, deterministically.
// - Events are pushed with EventKey{time, config.event_kind, owner, (left id << 32) | right id}
//   and a payload private to the structure. Whoever pops the queue calls handle_event(payload,
//   now) AFTER popping (the Simulator does so).
// - Keys contract: while neither motion changes, order_certificate(a, b, t) returns the same
//   origin at every t (e.g. the start of the current motion segments, not t itself), and
//   order_certificate(b, a, t).f is exactly -order_certificate(a, b, t).f (e.g. computed as
//   key_b - key_a coefficient-wise). Then an event is never re-fired at the instant it was
//   processed. Keys that re-centre at t still work but may cost extra events at near-ties.

#include <concepts>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>

#include "kinetic/core/event_queue.h"
#include "kinetic/sort/sort_config.h"
#include "kinetic/sort/sort_keys.h"
#include "kinetic/sort/sort_stats.h"

namespace kinray {

/// The common interface of KineticSortedList, KineticTournament and KineticHeap.
template <class S>
concept KineticSort =
    requires(S& s, const S& cs, uint32_t id, double t, uint64_t payload) {
      typename S::keys_type;
      requires KineticKeys<typename S::keys_type>;
      requires std::constructible_from<S, const typename S::keys_type&, EventQueue&, uint32_t,
                                       const KineticSortConfig&>;
      s.insert(id, t);
      s.erase(id, t);
      s.replace_motion(id, t);
      s.handle_event(payload, t);
      { cs.front() } -> std::same_as<std::optional<uint32_t>>;
      { cs.size() } -> std::convertible_to<size_t>;
      { cs.contains(id) } -> std::same_as<bool>;
      cs.audit(t);
      { cs.audit_problem(t) } -> std::same_as<std::optional<std::string>>;
      { cs.stats() } -> std::same_as<const KineticSortStats&>;
    };

}  // namespace kinray
