#pragma once
// Counters declared once. A structure's counters are one list, an X-macro of
// X(member, "stats key") lines; the struct's fields, its sum (over bands, pixels or instances),
// its total and the keys its --stats JSON uses are all generated from that list, so a new counter
// is one line and no writer can forget it or spell its key differently. (pbrt declares each
// STAT_COUNTER once for the same reason.)
#include <cstdint>

/// One field per counter of LIST, each starting at zero.
#define KINRAY_COUNTER_FIELD(member, key) uint64_t member = 0;
#define KINRAY_COUNTER_ADD(member, key) member += other.member;
#define KINRAY_COUNTER_PLUS(member, key) +member
#define KINRAY_COUNTER_VISIT(member, key) visit(key, member);

/// The members of a counter struct `Type` whose counters are LIST: the fields, `operator+=`, and
/// `for_each_counter(visit)`, which calls visit("stats key", value) for each counter in order.
#define KINRAY_COUNTERS(Type, LIST) KINRAY_COUNTERS_ADDING(Type, LIST, )

/// KINRAY_COUNTERS with a member `events` of type Events (a KINRAY_EVENT_COUNTERS struct) first,
/// summed by `operator+=` too; for_each_counter visits LIST only (the JSON writes the events as
/// their own section).
#define KINRAY_COUNTERS_WITH_EVENTS(Type, Events, LIST) \
  Events events;                                        \
  KINRAY_COUNTERS_ADDING(Type, LIST, events += other.events;)

#define KINRAY_COUNTERS_ADDING(Type, LIST, ALSO_ADD) \
  LIST(KINRAY_COUNTER_FIELD)                         \
  Type& operator+=(const Type& other) {              \
    ALSO_ADD                                         \
    LIST(KINRAY_COUNTER_ADD)                         \
    return *this;                                    \
  }                                                  \
  template <class Visit>                             \
  void for_each_counter(Visit&& visit) const {       \
    LIST(KINRAY_COUNTER_VISIT)                       \
  }

/// A member `function(visit)` that visits only the counters of LIST: a section of a struct whose
/// --stats JSON groups its counters (renderer/output/stats_json.h, section_json).
#define KINRAY_COUNTER_SECTION(function, LIST) \
  template <class Visit>                       \
  void function(Visit&& visit) const {         \
    LIST(KINRAY_COUNTER_VISIT)                 \
  }

/// KINRAY_COUNTERS for counts of events by kind, with `total()`, the sum over the kinds.
#define KINRAY_EVENT_COUNTERS(Type, LIST)                                      \
  KINRAY_COUNTERS(Type, LIST)                                                  \
  [[nodiscard]] uint64_t total() const { return 0 LIST(KINRAY_COUNTER_PLUS); }
