#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <set>
#include <string>
#include <tuple>
#include <unordered_map>
#include <vector>

#include "kinetic/core/event_queue.h"
#include "kinetic/core/simulator.h"

namespace kinray {
namespace {

auto as_tuple(const EventKey& k) { return std::make_tuple(k.time, k.kind, k.a, k.b); }

TEST(EventQueue, OrderIsLexicographic) {
  EXPECT_LT((EventKey{1, 5, 5, 5}), (EventKey{2, 0, 0, 0}));
  EXPECT_LT((EventKey{1, 0, 5, 5}), (EventKey{1, 1, 0, 0}));
  EXPECT_LT((EventKey{1, 1, 0, 5}), (EventKey{1, 1, 1, 0}));
  EXPECT_LT((EventKey{1, 1, 1, 0}), (EventKey{1, 1, 1, 1}));
  EXPECT_FALSE((EventKey{1, 1, 1, 1}) < (EventKey{1, 1, 1, 1}));
}

TEST(EventQueue, DeterministicTieOrder) {
  // Equal times pushed in several random orders always pop in (time, kind, a, b) order.
  std::vector<EventKey> keys;
  for (uint32_t kind = 0; kind < 3; ++kind)
    for (uint32_t a = 0; a < 3; ++a)
      for (uint64_t b = 0; b < 3; ++b) keys.push_back({1.0, kind, a, b});
  keys.push_back({0.5, 9, 9, 9});
  keys.push_back({2.0, 0, 0, 0});
  std::mt19937_64 rng(3);
  for (int round = 0; round < 20; ++round) {
    std::shuffle(keys.begin(), keys.end(), rng);
    EventQueue q;
    for (size_t i = 0; i < keys.size(); ++i) q.push(keys[i], i);
    EventKey previous{-1, 0, 0, 0};
    size_t popped = 0;
    while (!q.empty()) {
      const EventKey k = q.top_key();
      EXPECT_EQ(as_tuple(keys[q.top_payload()]), as_tuple(k));
      EXPECT_LT(previous, k);
      previous = k;
      q.pop();
      ++popped;
    }
    EXPECT_EQ(popped, keys.size());
  }
}

TEST(EventQueue, RandomOperationsAgainstMultiset) {
  std::mt19937_64 rng(12345);
  std::uniform_real_distribution<double> u(0, 100);
  EventQueue q;
  // Model: (time, kind, a, b, handle) so that ties are resolved as the queue does; payload = a
  // function of the handle's generation to catch stale slots.
  std::set<std::tuple<double, uint32_t, uint32_t, uint64_t, EventHandle>> model;
  std::vector<EventHandle> live;
  std::vector<uint64_t> payload_of(1, 0);
  uint64_t next_payload = 1;
  auto random_key = [&] {
    // Coarse times: many exact ties.
    return EventKey{std::floor(u(rng)) * 0.5, static_cast<uint32_t>(rng() % 3),
                    static_cast<uint32_t>(rng() % 4), rng() % 5};
  };
  for (int step = 0; step < 200000; ++step) {
    const int op = static_cast<int>(rng() % 10);
    if (op < 4 || live.empty()) {
      const EventKey k = random_key();
      const uint64_t p = next_payload++;
      const EventHandle h = q.push(k, p);
      ASSERT_FALSE(std::find(live.begin(), live.end(), h) != live.end());
      if (h >= payload_of.size()) payload_of.resize(h + 1);
      payload_of[h] = p;
      live.push_back(h);
      model.insert({k.time, k.kind, k.a, k.b, h});
    } else if (op < 6) {
      const size_t i = rng() % live.size();
      const EventHandle h = live[i];
      const EventKey old = q.key(h);
      const EventKey k = random_key();
      model.erase({old.time, old.kind, old.a, old.b, h});
      q.update(h, k);
      model.insert({k.time, k.kind, k.a, k.b, h});
      if (op == 5) {  // a new payload (with high bits, which the hint drops)
        payload_of[h] = (next_payload++) | (uint64_t{h} << 40);
        q.set_payload(h, payload_of[h]);
      }
    } else if (op < 8) {
      const size_t i = rng() % live.size();
      const EventHandle h = live[i];
      const EventKey old = q.key(h);
      ASSERT_EQ(q.payload(h), payload_of[h]);
      model.erase({old.time, old.kind, old.a, old.b, h});
      q.erase(h);
      EXPECT_FALSE(q.contains(h));
      live[i] = live.back();
      live.pop_back();
    } else {
      ASSERT_FALSE(q.empty());
      const auto& [time, kind, a, b, h_model] = *model.begin();
      const EventKey top = q.top_key();
      ASSERT_EQ(as_tuple(top), std::make_tuple(time, kind, a, b));
      // Equal full keys may come out in any handle order; compare keys, then drop that handle.
      const EventHandle h = q.top();
      ASSERT_EQ(q.top_payload(), payload_of[h]);
      ASSERT_EQ(q.top_payload_hint(), uint32_t(payload_of[h]));
      model.erase({time, kind, a, b, h});
      q.pop();
      live.erase(std::find(live.begin(), live.end(), h));
      (void)h_model;
    }
    ASSERT_EQ(q.size(), model.size());
    if (step % 5000 == 0) q.audit();
  }
  q.audit();
  EXPECT_GT(q.memory_bytes(), 0u);
  q.clear();
  EXPECT_TRUE(q.empty());
}

// The second hint (the event after the top one, a guess to prefetch by) names the event popped
// next after the top one whenever it names any: distinct random times, events pushed and popped.
TEST(EventQueue, SecondPayloadHintIsTheEventAfterTheTop) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1000.0);
  EventQueue q;
  std::set<std::pair<double, uint64_t>> model;  // (time, payload)
  uint64_t next_payload = 1;
  int named = 0;
  for (int step = 0; step < 20000; ++step) {
    if (rng() % 3 != 0 || model.size() < 2) {
      const double t = (model.empty() ? 0.0 : model.begin()->first) + u(rng);
      q.push(EventKey{t, 0, 0, 0}, next_payload);
      model.insert({t, next_payload++});
      continue;
    }
    const uint32_t second = q.second_payload_hint();
    if (second != kNoEvent) {
      ++named;
      ASSERT_EQ(second, uint32_t(std::next(model.begin())->second));
    }
    ASSERT_EQ(q.top_payload(), model.begin()->second);
    q.pop();
    model.erase(model.begin());
  }
  EXPECT_GT(named, 1000);  // the heap held the next event most of the time
}

// A kinetic simulation's pattern: most events are rescheduled far after the one being processed,
// so the queue keeps them in its time buckets and heapifies the next one as the heap runs dry;
// the events still come out in exact (time, kind, a, b) order, ties included.
TEST(EventQueue, RescheduledFarEventsComeOutInOrder) {
  std::mt19937_64 rng(777);
  std::exponential_distribution<double> later(1.0);
  EventQueue q;
  std::set<std::tuple<double, uint32_t, uint32_t, uint64_t, EventHandle>> model;
  std::vector<EventHandle> live;
  double now = 0;
  auto key_at = [&](double t) {
    // Times on a grid of 1/64: exact ties between near and far events.
    return EventKey{std::ceil(t * 64) / 64, static_cast<uint32_t>(rng() % 2),
                    static_cast<uint32_t>(rng() % 3), rng() % 3};
  };
  for (int i = 0; i < 20000; ++i) {
    const EventKey k = key_at(now + 50 * later(rng));
    const EventHandle h = q.push(k, 0);
    live.push_back(h);
    model.insert({k.time, k.kind, k.a, k.b, h});
  }
  for (int step = 0; step < 200000; ++step) {
    const int op = static_cast<int>(rng() % 10);
    if (op < 6) {
      ASSERT_FALSE(q.empty());
      const auto& [time, kind, a, b, h_model] = *model.begin();
      ASSERT_EQ(as_tuple(q.top_key()), std::make_tuple(time, kind, a, b));
      ASSERT_GE(time, now);
      now = time;
      const EventHandle h = q.top();
      model.erase({time, kind, a, b, h});
      q.pop();
      live.erase(std::find(live.begin(), live.end(), h));
      (void)h_model;
      // Rescheduled: usually much later, sometimes at this very instant.
      const EventKey k = key_at(op == 0 ? now : now + 50 * later(rng));
      const EventHandle n = q.push(k, 0);
      live.push_back(n);
      model.insert({k.time, k.kind, k.a, k.b, n});
    } else if (op < 9) {
      const EventHandle h = live[rng() % live.size()];
      const EventKey old = q.key(h);
      const EventKey k = key_at(now + (op == 6 ? 0.01 : 50) * later(rng));
      model.erase({old.time, old.kind, old.a, old.b, h});
      q.update(h, k);
      model.insert({k.time, k.kind, k.a, k.b, h});
    } else {
      const size_t i = rng() % live.size();
      const EventHandle h = live[i];
      const EventKey old = q.key(h);
      model.erase({old.time, old.kind, old.a, old.b, h});
      q.erase(h);
      live[i] = live.back();
      live.pop_back();
      const EventKey k = key_at(now + 50 * later(rng));
      const EventHandle n = q.push(k, 0);
      live.push_back(n);
      model.insert({k.time, k.kind, k.a, k.b, n});
    }
    ASSERT_EQ(q.size(), model.size());
    if (step % 997 == 0) q.audit();
  }
  while (!q.empty()) {
    const auto& [time, kind, a, b, h] = *model.begin();
    ASSERT_EQ(as_tuple(q.top_key()), std::make_tuple(time, kind, a, b));
    model.erase({time, kind, a, b, q.top()});
    q.pop();
  }
  q.audit();
}

// The calendar of time buckets under the distributions it handles worst: one burst of equal
// times (a zero-width calendar), times spread over twenty decades (most buckets empty, the rest
// crowded), and infinite times (always past the calendar); updates move events between buckets,
// into the heap and back out. The pops follow the sorted model exactly.
TEST(EventQueue, CalendarKeepsTheOrderOverAnySpreadOfTimes) {
  std::mt19937_64 rng(99);
  std::uniform_real_distribution<double> decade(-10, 10);
  const double inf = std::numeric_limits<double>::infinity();
  EventQueue q;
  std::set<std::tuple<double, uint32_t, uint32_t, uint64_t, EventHandle>> model;
  // The live handles, for picking one at random, and where each sits: a pop removes its handle
  // in constant time (a search of the 23,000 took most of this test's time).
  std::vector<EventHandle> live;
  std::unordered_map<EventHandle, size_t> slot;
  auto forget = [&](EventHandle h) {
    const size_t i = slot.at(h);
    live[i] = live.back();
    slot[live[i]] = i;
    live.pop_back();
    slot.erase(h);
  };
  double now = 0;
  uint64_t serial = 0;  // unique keys: the order is total, handles never break a tie
  auto key_at = [&](int mode) {
    const double t = mode == 0 ? now : (mode == 1 ? inf : now + std::pow(10.0, decade(rng)));
    return EventKey{t, static_cast<uint32_t>(rng() % 2), static_cast<uint32_t>(rng() % 2), ++serial};
  };
  auto push = [&](const EventKey& k) {
    const EventHandle h = q.push(k, 0);
    slot[h] = live.size();
    live.push_back(h);
    model.insert({k.time, k.kind, k.a, k.b, h});
  };
  for (int i = 0; i < 3000; ++i) push(EventKey{1.0, 0, uint32_t(i), ++serial});  // one instant
  for (int i = 0; i < 20000; ++i) push(key_at(i % 50 == 0 ? 1 : 2));
  for (int step = 0; step < 100000; ++step) {
    const int op = static_cast<int>(rng() % 8);
    if (op < 5) {
      const auto& [time, kind, a, b, h] = *model.begin();
      ASSERT_EQ(as_tuple(q.top_key()), std::make_tuple(time, kind, a, b));
      ASSERT_EQ(q.top(), h);
      if (std::isfinite(time)) now = time;
      model.erase(model.begin());
      forget(q.top());
      q.pop();
      push(key_at(op == 0 ? 0 : (op == 1 ? 1 : 2)));
    } else {
      const size_t i = rng() % live.size();
      const EventHandle h = live[i];
      const EventKey old = q.key(h);
      const EventKey k = key_at(op == 5 ? 0 : 2);
      model.erase({old.time, old.kind, old.a, old.b, h});
      if (op == 7) {
        q.erase(h);
        forget(h);
        push(k);
      } else {
        q.update(h, k);
        model.insert({k.time, k.kind, k.a, k.b, h});
      }
    }
    ASSERT_EQ(q.size(), model.size());
    if (step % 4999 == 0) q.audit();
  }
  while (!q.empty()) {
    const auto& [time, kind, a, b, h] = *model.begin();
    ASSERT_EQ(as_tuple(q.top_key()), std::make_tuple(time, kind, a, b));
    ASSERT_EQ(q.top(), h);
    model.erase(model.begin());
    q.pop();
  }
  q.audit();
}

TEST(EventQueue, CalendarIsLaidAgainWhenTheQueueOutgrowsIt) {
  // A calendar laid over a few events and then filled by bursts of pushes many times their
  // number (a band's initialisation, a keyframe) is laid again at a refill; calendars of many
  // and of few buckets alternate, so the buckets kept from one serve the next. The order stays
  // that of a sorted list and the positions stay consistent.
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> unit(0, 1);
  EventQueue q;
  std::set<std::tuple<double, uint32_t, uint32_t, uint64_t, EventHandle>> model;
  uint64_t serial = 0;
  double now = 0;
  auto push = [&](double t) {
    const EventKey k{t, 0, 0, ++serial};
    model.insert({k.time, k.kind, k.a, k.b, q.push(k, serial)});
  };
  auto pop = [&] {
    const auto& [time, kind, a, b, h] = *model.begin();
    ASSERT_EQ(as_tuple(q.top_key()), std::make_tuple(time, kind, a, b));
    ASSERT_EQ(q.top(), h);
    now = time;
    model.erase(model.begin());
    q.pop();
  };
  for (int burst : {10, 40000, 300, 60000, 5, 20000}) {
    for (int i = 0; i < burst; ++i) push(now + unit(rng));
    for (int i = 0; i < 2 * burst / 3 + 1; ++i) {
      pop();
      if (i % 4 == 0) push(now + 0.01 * unit(rng));  // events near now, into the heap
    }
    q.audit();
  }
  while (!q.empty()) pop();
  q.audit();
}

TEST(EventQueue, SimulatorAdvanceTo) {
  Simulator sim(1.0);
  EXPECT_EQ(sim.now(), 1.0);
  std::vector<std::pair<double, uint64_t>> seen;
  sim.queue().push({3.0, 0, 0, 0}, 30);
  sim.queue().push({2.0, 0, 0, 0}, 20);
  sim.queue().push({5.0, 0, 0, 0}, 50);
  sim.advance_to(4.0, [&](const EventKey& k, uint64_t payload) {
    EXPECT_EQ(sim.now(), k.time);
    seen.push_back({k.time, payload});
    if (payload == 20) {
      // Scheduled during handling, at a time <= t: processed in the same call, in order.
      sim.queue().push({2.0, 1, 0, 0}, 21);
      sim.queue().push({3.5, 0, 0, 0}, 35);
      sim.queue().push({4.5, 0, 0, 0}, 45);
    }
  });
  EXPECT_EQ(sim.now(), 4.0);
  const std::vector<std::pair<double, uint64_t>> expected{{2.0, 20}, {2.0, 21}, {3.0, 30},
                                                          {3.5, 35}};
  EXPECT_EQ(seen, expected);
  EXPECT_EQ(sim.next_event_time(), 4.5);
  EXPECT_EQ(sim.events_processed(), 4u);
  sim.advance_to(4.0, [&](const EventKey&, uint64_t) { FAIL(); });  // nothing at <= 4
  EXPECT_DEATH(sim.advance_to(3.0, [](const EventKey&, uint64_t) {}), "t >= m_now \\(3 vs 4\\)");
  sim.queue().push({3.9, 0, 0, 0}, 39);  // in the past
  EXPECT_DEATH(sim.advance_to(5.0, [](const EventKey&, uint64_t) {}), "past");
}

TEST(EventQueue, ScheduleIsPushMoveOrCancelThroughTheOwnersHandle) {
  EventQueue q;
  EventHandle h = kNoEvent;
  q.schedule(h, {2.0, 1, 7, 0}, 70);  // nothing pending: a push
  ASSERT_NE(h, kNoEvent);
  EXPECT_EQ(q.size(), 1u);
  EventHandle other = kNoEvent;
  q.schedule(other, {1.0, 1, 8, 0}, 80);
  EXPECT_EQ(q.top_payload(), 80u);
  const EventHandle first = h;
  q.schedule(h, {0.5, 1, 7, 1}, 71);  // pending: moved in place, with its new key and payload
  EXPECT_EQ(h, first);
  EXPECT_EQ(q.size(), 2u);
  EXPECT_EQ(q.top_key().b, 1u);
  EXPECT_EQ(q.top_payload(), 71u);
  q.schedule(h, {std::numeric_limits<double>::infinity(), 1, 7, 0}, 72);  // never: cancelled
  EXPECT_EQ(h, kNoEvent);
  EXPECT_EQ(q.size(), 1u);
  q.schedule(h, {std::numeric_limits<double>::infinity(), 1, 7, 0}, 72);  // nothing to cancel
  EXPECT_EQ(h, kNoEvent);
  q.cancel(other);
  EXPECT_EQ(other, kNoEvent);
  EXPECT_TRUE(q.empty());
  q.cancel(other);  // a no-op on an empty slot
  q.audit();
}

TEST(EventQueue, SimulatorPrefetchHookSeesEachEventBeforeItsPopAndTheNextAfter) {
  Simulator sim;
  sim.start_at(1.0);
  EXPECT_EQ(sim.now(), 1.0);
  for (uint64_t k = 2; k <= 5; ++k) sim.queue().push({double(k), 0, 0, 0}, k);
  std::vector<std::string> trace;
  struct Hook {
    std::vector<std::string>* trace;
    void before_pop(const EventKey& key, uint64_t payload) const {
      trace->push_back("before " + std::to_string(payload) + " at " + std::to_string(int(key.time)));
    }
    void after_pop(const EventQueue& queue) const {
      trace->push_back("next " + std::to_string(queue.top_payload_hint()));
    }
  };
  sim.advance_to(
      4.0, [&](const EventKey&, uint64_t payload) { trace.push_back("handle " + std::to_string(payload)); },
      Hook{&trace});
  const std::vector<std::string> expected{"before 2 at 2", "next 3", "handle 2",
                                          "before 3 at 3", "next 4", "handle 3",
                                          "before 4 at 4", "next 5", "handle 4"};
  EXPECT_EQ(trace, expected);
  trace.clear();
  sim.advance_to(6.0, [&](const EventKey&, uint64_t payload) { trace.push_back("handle " + std::to_string(payload)); },
                 Hook{&trace});
  // The last event: nothing is left at the top after its pop.
  EXPECT_EQ(trace, (std::vector<std::string>{"before 5 at 5", "handle 5"}));
  EXPECT_DEATH(sim.start_at(0.0), "m_events == 0");
}

}  // namespace
}  // namespace kinray
