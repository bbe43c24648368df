#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "kinetic/core/simulator.h"
#include "kinetic/sort/kinetic_heap.h"
#include "kinetic/sort/kinetic_sort.h"
#include "kinetic/sort/kinetic_sorted_list.h"
#include "kinetic/sort/linear_motion_keys.h"
#include "kinetic/sort/polynomial_keys.h"
#include "kinetic/sort/kinetic_tournament.h"

namespace kinray {
namespace {

constexpr uint32_t kOwner = 7;
constexpr uint32_t kKind = 3;

template <class S>
constexpr bool kIsList = std::is_same_v<S, KineticSortedList<typename S::keys_type>>;

static_assert(KineticSort<KineticSortedList<PolynomialKeys>>);
static_assert(KineticSort<KineticTournament<PolynomialKeys>>);
static_assert(KineticSort<KineticHeap<PolynomialKeys>>);
static_assert(KineticSort<KineticSortedList<LinearMotionKeys>>);

double tolerance(double v) { return 1e-9 * (1 + std::fabs(v)); }

// One structure on its own simulator, with audit on, and a brute-force model of its members.
template <class S>
struct Harness {
  typename S::keys_type keys;
  Simulator sim;
  S s;
  std::set<uint32_t> members;
  uint64_t checks = 0;

  Harness() : s(keys, sim.queue(), kOwner, KineticSortConfig{kKind, true}) {}

  void advance(double t) {
    sim.advance_to(t, [&](const EventKey& k, uint64_t payload) {
      ASSERT_EQ(k.a, kOwner);
      ASSERT_EQ(k.kind, kKind);
      s.handle_event(payload, sim.now());
    });
  }
  void insert(uint32_t id) {
    s.insert(id, sim.now());
    members.insert(id);
  }
  void erase(uint32_t id) {
    s.erase(id, sim.now());
    members.erase(id);
  }
  // front() (and the whole order for the sorted list) against a brute-force sort at now().
  void check() {
    ++checks;
    const double t = sim.now();
    s.audit(t);
    ASSERT_EQ(s.size(), members.size());
    if (members.empty()) {
      ASSERT_FALSE(s.front());
      return;
    }
    double lowest = std::numeric_limits<double>::infinity();
    for (uint32_t id : members) lowest = std::min(lowest, keys.value(id, t));
    ASSERT_TRUE(s.front());
    ASSERT_TRUE(members.count(*s.front()));
    const double front_value = keys.value(*s.front(), t);
    ASSERT_LE(front_value, lowest + tolerance(lowest)) << "t = " << t;
    if constexpr (kIsList<S>) {
      std::vector<uint32_t> order;
      s.for_each_in_order([&](uint32_t id) { order.push_back(id); });
      ASSERT_EQ(order.size(), members.size());
      ASSERT_EQ(std::set<uint32_t>(order.begin(), order.end()), members);
      for (size_t i = 0; i + 1 < order.size(); ++i) {
        const double va = keys.value(order[i], t), vb = keys.value(order[i + 1], t);
        ASSERT_LE(va, vb + tolerance(vb)) << "t = " << t << " at " << i << " ids " << order[i]
                                          << ", " << order[i + 1] << " degenerate "
                                          << s.stats().degenerate;
      }
    }
  }
};

template <class S>
class KineticSort : public ::testing::Test {};

using Structures = ::testing::Types<KineticSortedList<PolynomialKeys>,
                                    KineticTournament<PolynomialKeys>, KineticHeap<PolynomialKeys>>;
struct StructureNames {
  template <class S>
  static std::string GetName(int) {
    if constexpr (std::is_same_v<S, KineticSortedList<PolynomialKeys>>) return "SortedList";
    if constexpr (std::is_same_v<S, KineticTournament<PolynomialKeys>>) return "Tournament";
    return "Heap";
  }
};
TYPED_TEST_SUITE(KineticSort, Structures, StructureNames);

TYPED_TEST(KineticSort, TwoObjectsSwapAtTheExactTime) {
  Harness<TypeParam> h;
  const uint32_t a = h.keys.add(Polynomial{0, 1});  // t
  const uint32_t b = h.keys.add(Polynomial{1});     // 1
  h.insert(b);
  h.insert(a);
  ASSERT_EQ(h.s.front(), a);
  ASSERT_EQ(h.sim.queue().size(), 1u);
  EXPECT_EQ(h.sim.queue().top_key().time, 1.0);
  h.advance(0.999);
  EXPECT_EQ(h.s.front(), a);
  h.advance(1.0);
  EXPECT_EQ(h.s.front(), b);  // processed at t = 1: from then on b is ahead
  h.check();
  h.advance(5);
  EXPECT_EQ(h.s.front(), b);
  EXPECT_EQ(h.s.stats().events_external, 1u);
  EXPECT_EQ(h.s.stats().certificates_live, 1u);
  EXPECT_TRUE(h.sim.queue().empty());
}

TYPED_TEST(KineticSort, TouchIsNotAnEvent) {
  Harness<TypeParam> h;
  const uint32_t a = h.keys.add(Polynomial{1, -2, 1});  // (t - 1)^2 touches 0 at t = 1
  const uint32_t b = h.keys.add(Polynomial{0});
  h.insert(a);
  h.insert(b);
  EXPECT_EQ(h.s.front(), b);
  h.advance(3);
  h.check();
  EXPECT_EQ(h.s.front(), b);
  EXPECT_EQ(h.s.stats().events(), 0u);
}

TYPED_TEST(KineticSort, IdenticalMotionsAreOrderedById) {
  Harness<TypeParam> h;
  std::vector<uint32_t> ids;
  for (int i = 0; i < 12; ++i) ids.push_back(h.keys.add(Polynomial{2, -1, 0.25}));
  std::mt19937_64 rng(5);
  std::shuffle(ids.begin(), ids.end(), rng);
  for (uint32_t id : ids) h.insert(id);
  EXPECT_EQ(h.s.front(), 0u);
  if constexpr (kIsList<TypeParam>) {
    uint32_t expected = 0;
    h.s.for_each_in_order([&](uint32_t id) { EXPECT_EQ(id, expected++); });
  }
  h.advance(10);
  EXPECT_EQ(h.s.front(), 0u);
  EXPECT_EQ(h.s.stats().events(), 0u);
  // Object 5 dips below the others on [11, 12) and rejoins them exactly from t = 12 on: then it
  // ties with all of them (zero certificates) and is ordered by id again.
  h.advance(11);
  const Polynomial common{2, -1, 0.25};
  const double v11 = common(11.0), v12 = common(12.0);
  h.keys.set_motion(5, Polynomial{v11 - 1, v12 - v11 + 1}, 11);
  h.keys.append_motion(5, shifted(common, 12), 12);
  h.s.replace_motion(5, 11);
  h.advance(11.5);
  EXPECT_EQ(h.s.front(), 5u);
  h.check();
  h.advance(13);
  EXPECT_EQ(h.s.front(), 0u);
  h.check();
  if constexpr (kIsList<TypeParam>) {
    uint32_t expected = 0;
    h.s.for_each_in_order([&](uint32_t id) { EXPECT_EQ(id, expected++); });
  }
}

TYPED_TEST(KineticSort, SimultaneousCrossingOfManyObjects) {
  Harness<TypeParam> h;
  // x_i(t) = v_i (t - 1): all cross at t = 1 exactly (c0 = -c1 bit for bit).
  constexpr int kN = 25;
  for (int i = 0; i < kN; ++i) {
    const double v = (i - 12) * 0.37;
    h.insert(h.keys.add(Polynomial{-v, v}));
  }
  h.check();
  h.advance(1.0);
  h.check();
  h.advance(2.0);
  h.check();
  EXPECT_EQ(h.s.front(), static_cast<uint32_t>(0));  // the most negative velocity
  EXPECT_EQ(h.s.stats().degenerate, 0u);
}

TYPED_TEST(KineticSort, RenewalAtTheEndOfAMotionSegment) {
  Harness<TypeParam> h;
  const uint32_t a = h.keys.add(Polynomial{0});  // at 0
  const uint32_t b = h.keys.add(Polynomial{1});  // at 1, then from t = 2 falls at speed 1
  h.keys.append_motion(b, Polynomial{1, -1}, 2);
  h.insert(a);
  h.insert(b);
  h.advance(2.5);
  EXPECT_EQ(h.s.front(), a);
  h.advance(3.5);  // b crosses a at t = 3, found after the renewal at t = 2
  EXPECT_EQ(h.s.front(), b);
  h.check();
  EXPECT_EQ(h.s.stats().events_renewal, 1u);
  EXPECT_EQ(h.s.stats().events_external, 1u);
}

// Random linear and quadratic motions, equal keys, insertions and deletions at random times,
// motions replaced mid-run (continuous and jumping) and future segments; audit after every event.
TYPED_TEST(KineticSort, RandomMotionsAgainstBruteForce) {
  uint64_t events = 0;
  for (uint64_t seed = 1; seed <= 20; ++seed) {
    Harness<TypeParam> h;
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u(-1, 1);
    auto random_motion = [&](double value_now) {
      const bool quadratic = rng() % 2;
      return Polynomial{value_now, 3 * u(rng), quadratic ? 0.5 * u(rng) : 0.0};
    };
    auto new_object = [&]() {
      if (h.keys.size() > 0 && rng() % 8 == 0)  // equal keys: an exact copy of another's motion
        return h.keys.add_copy(static_cast<uint32_t>(rng() % h.keys.size()));
      return h.keys.add(random_motion(5 * u(rng)), h.sim.now());
    };
    // Odd seeds start above 64 objects: the tournament and heap then use their id index.
    const int initial = seed % 2 ? 90 : 30;
    for (int i = 0; i < initial; ++i) h.insert(new_object());
    h.check();
    double t = 0;
    while (t < 15) {
      t += 0.25 * (u(rng) + 1.0001);
      h.advance(t);
      ASSERT_NO_FATAL_FAILURE(h.check());
      const int op = static_cast<int>(rng() % 10);
      if (op == 0 && h.members.size() < 120) {
        h.insert(new_object());
      } else if (op == 1 && !h.members.empty()) {
        auto it = h.members.begin();
        std::advance(it, static_cast<long>(rng() % h.members.size()));
        h.erase(*it);
      } else if (op == 2 && !h.members.empty()) {
        auto it = h.members.begin();
        std::advance(it, static_cast<long>(rng() % h.members.size()));
        const uint32_t id = *it;
        const double jump = rng() % 3 == 0 ? 2 * u(rng) : 0.0;
        h.keys.set_motion(id, random_motion(h.keys.value(id, t) + jump), t);
        h.s.replace_motion(id, t);
      } else if (op == 3 && !h.members.empty()) {
        auto it = h.members.begin();
        std::advance(it, static_cast<long>(rng() % h.members.size()));
        const uint32_t id = *it;
        const double later = t + 0.5 * (u(rng) + 1.01);
        h.keys.append_motion(id, random_motion(h.keys.value(id, later)), later);
        h.s.replace_motion(id, t);  // its certificates must learn their new end
      }
      h.advance(t);  // events at t created by a jump in motion are processed now
      ASSERT_NO_FATAL_FAILURE(h.check());
    }
    EXPECT_EQ(h.s.stats().certificates_live, h.members.empty() ? 0 : h.members.size() - 1);
    events += h.s.stats().events();
  }
  EXPECT_GT(events, 200u);
}

// A flightplan update of many members at once (a mesh key in a pixel): replace_motions computes
// each certificate with a moved member once (the sorted list: one per adjacent pair with a moved
// member, where replace_motion member by member computes a pair of two moved members twice),
// and the structure then runs exactly as with replace_motion.
TYPED_TEST(KineticSort, ReplaceMotionsRunsLikeReplaceMotionMemberByMember) {
  Harness<TypeParam> once, each;
  std::mt19937_64 rng(41);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<Polynomial> start, moved;
  for (int i = 0; i < 40; ++i) {
    start.push_back(Polynomial{5 * u(rng), u(rng), 0.2 * u(rng)});
    moved.push_back(Polynomial{5 * u(rng), u(rng), 0.2 * u(rng)});
  }
  for (Harness<TypeParam>* h : {&once, &each}) {
    for (const Polynomial& p : start) h->insert(h->keys.add(p));
    h->advance(1);
  }
  // at t = 1 the even ids switch motion, continuously (the same value at 1); member by member,
  // each is replaced as it switches (the audit sees no stale certificate between the calls)
  const double t = 1;
  const uint64_t work_once = once.s.stats().work, work_each = each.s.stats().work;
  for (uint32_t id = 0; id < 40; id += 2) {
    for (Harness<TypeParam>* h : {&once, &each}) {
      Polynomial p = moved[id];
      p.c[0] = h->keys.value(id, t);  // local time from t
      h->keys.set_motion(id, p, t);
    }
    each.s.replace_motion(id, t);
  }
  once.s.replace_motions([](uint32_t id) { return id % 2 == 0; }, t);
  EXPECT_LT(once.s.stats().work - work_once, each.s.stats().work - work_each);
  if constexpr (kIsList<TypeParam>) {
    // every adjacent pair has a moved member unless both are odd; pairs of two even ids count
    // twice member by member
    std::vector<uint32_t> order;
    once.s.for_each_in_order([&](uint32_t id) { order.push_back(id); });
    uint64_t pairs = 0, both = 0;
    for (size_t i = 0; i + 1 < order.size(); ++i) {
      const bool a = order[i] % 2 == 0, b = order[i + 1] % 2 == 0;
      pairs += a || b;
      both += a && b;
    }
    EXPECT_EQ(once.s.stats().work - work_once, pairs);
    EXPECT_EQ(each.s.stats().work - work_each, pairs + both);
  }
  for (double at = 1.5; at <= 6; at += 0.5) {
    once.advance(at);
    each.advance(at);
    ASSERT_NO_FATAL_FAILURE(once.check());
    ASSERT_EQ(once.s.front(), each.s.front()) << "t = " << at;
  }
  EXPECT_EQ(once.s.stats().events(), each.s.stats().events());
  EXPECT_GT(once.s.stats().events(), 10u);  // the structure did run
}

TYPED_TEST(KineticSort, InsertAllThenSimulate) {
  Harness<TypeParam> h;
  std::mt19937_64 rng(31);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<uint32_t> first, second;
  for (int i = 0; i < 100; ++i) first.push_back(h.keys.add(Polynomial{10 * u(rng), u(rng)}));
  for (int i = 0; i < 5; ++i) first.push_back(h.keys.add_copy(first[i]));  // equal keys
  for (int i = 0; i < 50; ++i) second.push_back(h.keys.add(Polynomial{10 * u(rng), u(rng)}));
  h.s.insert_all(first, 0);
  h.members.insert(first.begin(), first.end());
  h.advance(0);
  h.check();
  h.advance(3);
  h.s.insert_all(second, 3);  // merged into a non-empty structure
  h.members.insert(second.begin(), second.end());
  h.advance(3);
  h.check();
  for (double t = 3.5; t < 12; t += 0.5) {
    h.advance(t);
    ASSERT_NO_FATAL_FAILURE(h.check());
  }
  EXPECT_EQ(h.s.stats().certificates_live, h.members.size() - 1);
}

// Small integer motions: many exact simultaneous crossings (three or more lines through a point,
// parabolas meeting lines at a tangent), the degenerate cases of kinetic sorting.
TYPED_TEST(KineticSort, DegenerateIntegerMotions) {
  Harness<TypeParam> h;
  std::mt19937_64 rng(17);
  for (int i = 0; i < 40; ++i) {
    const double x = static_cast<double>(rng() % 7) - 3, v = static_cast<double>(rng() % 5) - 2;
    const double a = rng() % 4 == 0 ? (static_cast<double>(rng() % 3) - 1) * 0.5 : 0.0;
    h.insert(h.keys.add(Polynomial{x, v, a}));
  }
  for (double t = 0.125; t <= 8; t += 0.125) {  // also exactly at many event times
    h.advance(t);
    ASSERT_NO_FATAL_FAILURE(h.check());
  }
  EXPECT_GT(h.s.stats().events(), 10u);
}

// Keys that re-centre every certificate at t (breaking the same-origin recommendation): still
// correct, through the decision by sign at the event and the same-instant guard.
class RecentredKeys {
 public:
  explicit RecentredKeys(const PolynomialKeys& keys) : m_keys(&keys) {}
  OrderCertificate order_certificate(uint32_t a, uint32_t b, double t) const {
    OrderCertificate c = m_keys->order_certificate(a, b, t);
    c.f = shifted(c.f, t - c.origin);
    c.origin = t;
    return c;
  }
  double value(uint32_t a, double t) const { return m_keys->value(a, t); }

 private:
  const PolynomialKeys* m_keys;
};

template <class S>
void run_recentred() {
  PolynomialKeys base;
  RecentredKeys keys(base);
  Simulator sim;
  S s(keys, sim.queue(), 1, KineticSortConfig{0, true});
  std::mt19937_64 rng(23);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int i = 0; i < 40; ++i) s.insert(base.add(Polynomial{5 * u(rng), u(rng), 0.2 * u(rng)}), 0);
  for (double t = 0.3; t < 10; t += 0.3) {
    sim.advance_to(t, [&](const EventKey&, uint64_t payload) { s.handle_event(payload, sim.now()); });
    double lowest = std::numeric_limits<double>::infinity();
    for (uint32_t id = 0; id < base.size(); ++id) lowest = std::min(lowest, base.value(id, t));
    ASSERT_LE(base.value(*s.front(), t), lowest + tolerance(lowest));
  }
  EXPECT_GT(s.stats().events(), 10u);
}

// Keys whose certificates keep ending at t = 2 (the owner has not switched motions yet): one
// renewal at 2, then no event loop at that instant.
class StaleEndKeys {
 public:
  explicit StaleEndKeys(const PolynomialKeys& keys) : m_keys(&keys) {}
  OrderCertificate order_certificate(uint32_t a, uint32_t b, double t) const {
    OrderCertificate c = m_keys->order_certificate(a, b, t);
    c.end = 2;
    return c;
  }
  double value(uint32_t a, double t) const { return m_keys->value(a, t); }

 private:
  const PolynomialKeys* m_keys;
};

TEST(KineticSortStaleEnd, NoRenewalLoop) {
  PolynomialKeys base;
  StaleEndKeys keys(base);
  Simulator sim;
  KineticSortedList<StaleEndKeys> list(keys, sim.queue(), 0);
  list.insert(base.add(Polynomial{0, 1}), 0);
  list.insert(base.add(Polynomial{10}), 0);
  sim.advance_to(5, [&](const EventKey&, uint64_t payload) { list.handle_event(payload, sim.now()); });
  EXPECT_EQ(list.stats().events_renewal, 1u);
  EXPECT_TRUE(sim.queue().empty());
}

TEST(KineticSortRecentred, AllStructures) {
  run_recentred<KineticSortedList<RecentredKeys>>();
  run_recentred<KineticTournament<RecentredKeys>>();
  run_recentred<KineticHeap<RecentredKeys>>();
}

// The grid's use: many small instances (1-10 objects) share one queue and one stats total.
TYPED_TEST(KineticSort, ManySmallInstancesShareOneQueue) {
  using Keys = typename TypeParam::keys_type;
  Keys keys;
  Simulator sim;
  KineticSortStats total;
  std::mt19937_64 rng(99);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int i = 0; i < 400; ++i) keys.add(Polynomial{5 * u(rng), 2 * u(rng), 0.3 * u(rng)});
  std::vector<TypeParam> pixels;
  std::vector<std::vector<uint32_t>> members(300);
  pixels.reserve(300);
  for (uint32_t p = 0; p < 300; ++p) {
    pixels.emplace_back(keys, sim.queue(), p, KineticSortConfig{1, false, &total});
    const size_t n = 1 + rng() % 10;
    while (members[p].size() < n) {
      const auto id = static_cast<uint32_t>(rng() % keys.size());
      if (std::find(members[p].begin(), members[p].end(), id) != members[p].end()) continue;
      members[p].push_back(id);
      pixels[p].insert(id, 0);
    }
  }
  for (double t = 0.1; t < 10; t += 0.37) {
    sim.advance_to(t, [&](const EventKey& k, uint64_t payload) {
      pixels[k.a].handle_event(payload, sim.now());
    });
    for (uint32_t p = 0; p < 300; p += 7) {
      pixels[p].audit(t);
      double lowest = std::numeric_limits<double>::infinity();
      for (uint32_t id : members[p]) lowest = std::min(lowest, keys.value(id, t));
      ASSERT_LE(keys.value(*pixels[p].front(), t), lowest + tolerance(lowest));
    }
  }
  EXPECT_GT(total.events(), 100u);
  EXPECT_EQ(&pixels[0].stats(), &total);
  const QualityMeasures q = quality_measures(quality_counts(total, 1650));
  EXPECT_GT(q.responsiveness, 0);
  EXPECT_LT(pixels[0].memory_bytes(), 512u);
}

TEST(KineticSortIdIndex, RandomAgainstUnorderedMap) {
  detail::IdIndex index;
  std::map<uint32_t, uint32_t> model;
  std::mt19937_64 rng(41);
  for (int step = 0; step < 200000; ++step) {
    const auto id = static_cast<uint32_t>(rng() % 3000) * 7919u;  // clustered hash homes
    switch (rng() % 3) {
      case 0:
      case 1: {
        const auto pos = static_cast<uint32_t>(rng() % 100000);
        index.set(id, pos);
        model[id] = pos;
        break;
      }
      default:
        index.erase(id);
        model.erase(id);
    }
    if (step % 1000 == 0) {
      ASSERT_EQ(index.size(), model.size());
      for (const auto& [k, v] : model) ASSERT_EQ(index.find(k), v);
    }
    const auto probe = static_cast<uint32_t>(rng() % 3000) * 7919u;
    const auto it = model.find(probe);
    ASSERT_EQ(index.find(probe), it == model.end() ? detail::IdIndex::kMissing : it->second);
  }
}

TEST(KineticSortLinear, SortedListWithLinearMotionKeys) {
  LinearMotionKeys keys;
  Simulator sim;
  KineticSortedList<LinearMotionKeys> list(keys, sim.queue(), 0, {0, true});
  std::mt19937_64 rng(8);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int i = 0; i < 200; ++i) list.insert(keys.add(10 * u(rng), u(rng)), 0);
  for (double t = 0.5; t <= 20; t += 0.5) {
    sim.advance_to(t, [&](const EventKey&, uint64_t payload) { list.handle_event(payload, sim.now()); });
    double previous = -std::numeric_limits<double>::infinity();
    list.for_each_in_order([&](uint32_t id) {
      EXPECT_GE(keys.value(id, t), previous);
      previous = keys.value(id, t);
    });
  }
  EXPECT_GT(list.stats().events(), 1000u);
}

// Two sorted lists of the same keys, each on its own simulator with the audit on: `a` takes
// replacements in place, `b` always erases and inserts. After every step both must hold the same
// order and the same next event.
template <class Keys>
struct TwinLists {
  explicit TwinLists(const Keys& keys)
      : a(keys, sim_a.queue(), 0, {0, true}), b(keys, sim_b.queue(), 0, {0, true}) {}
  void insert(uint32_t id) {
    a.insert(id, 0);
    b.insert(id, 0);
  }
  static std::vector<uint32_t> order(const KineticSortedList<Keys>& list) {
    std::vector<uint32_t> ids;
    list.for_each_in_order([&](uint32_t id) { ids.push_back(id); });
    return ids;
  }
  void advance_to(double t) {
    sim_a.advance_to(t, [&](const EventKey&, uint64_t payload) { a.handle_event(payload, t); });
    sim_b.advance_to(t, [&](const EventKey&, uint64_t payload) { b.handle_event(payload, t); });
    ASSERT_EQ(order(a), order(b)) << "t = " << t;
  }
  /// `a` has replaced `from` by `to` at t (in place, or by erase and insert): `b` erases and
  /// inserts, and the two must agree.
  void expect_replaced(uint32_t from, uint32_t to, double t) {
    b.erase(from, t);
    b.insert(to, t);
    ASSERT_EQ(order(a), order(b)) << "t = " << t;
    ASSERT_EQ(sim_a.queue().size(), sim_b.queue().size());
    if (!sim_a.queue().empty()) {
      ASSERT_EQ(sim_a.queue().top_key().time, sim_b.queue().top_key().time) << "t = " << t;
    }
  }
  Simulator sim_a, sim_b;
  KineticSortedList<Keys> a, b;
};

// A pixel's triangle handing over to its neighbour across an edge (the grid's boundary events):
// replace_in_place puts the new object at the old one's place when both neighbours' certificates
// agree, and must leave the list as erase then insert would, then and at every later event; when
// they disagree it changes nothing. New objects at the old one's value (the hand-over) and
// anywhere (the disagreeing case), against a second list that always erases and inserts.
TEST(KineticSortLinear, ReplaceInPlaceIsEraseThenInsert) {
  LinearMotionKeys keys;
  TwinLists<LinearMotionKeys> lists(keys);
  std::mt19937_64 rng(31);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<uint32_t> members;
  for (int i = 0; i < 7; ++i) {
    members.push_back(keys.add(4 * u(rng), u(rng)));
    lists.insert(members.back());
  }
  int in_place = 0, refused = 0;
  for (int step = 1; step <= 400; ++step) {
    const double t = 0.05 * step;
    ASSERT_NO_FATAL_FAILURE(lists.advance_to(t));
    const size_t k = size_t(rng() % members.size());
    const uint32_t from = members[k];
    // At from's value now (a hand-over), or at a random value (mostly out of place).
    const double v = u(rng), at = step % 3 == 0 ? 4 * u(rng) : keys.value(from, t);
    const uint32_t to = keys.add(at - v * t, v);
    const std::vector<uint32_t> before = lists.order(lists.a);
    if (lists.a.replace_in_place(from, to, t)) {
      ++in_place;
    } else {
      ++refused;
      ASSERT_EQ(lists.order(lists.a), before);
      lists.a.erase(from, t);
      lists.a.insert(to, t);
    }
    members[k] = to;
    ASSERT_NO_FATAL_FAILURE(lists.expect_replaced(from, to, t));
  }
  EXPECT_EQ(lists.a.stats().events(), lists.b.stats().events());
  EXPECT_GT(in_place, 200);
  EXPECT_GT(refused, 50);
}

// Lines x0 + v t whose certificates all end at a horizon: a pair whose ranges over [now, horizon]
// do not overlap is apart, with the float midpoint of the gap as its separator (the pixel
// orders' depth_order_apart, in one dimension), and a replacement is compared with a separator
// alone (SeparatorKeys).
class HorizonLineKeys {
 public:
  explicit HorizonLineKeys(double horizon) : m_horizon(horizon) {}
  uint32_t add(double x0, double v) {
    m_lines.push_back({x0, v});
    return uint32_t(m_lines.size() - 1);
  }
  [[nodiscard]] OrderCertificate order_certificate(uint32_t a, uint32_t b, double now) const {
    OrderCertificate c;
    c.end = m_horizon;
    const auto [a_lo, a_hi] = range(a, now);
    const auto [b_lo, b_hi] = range(b, now);
    // The gap between the lower one's top and the upper one's bottom, the same for (a, b) and
    // (b, a); its float midpoint separates them when it lies strictly inside.
    const bool a_below = a_hi < b_lo;
    if (a_below || b_hi < a_lo) {
      const double gap_lo = a_below ? a_hi : b_hi, gap_hi = a_below ? b_lo : a_lo;
      const float z = midpoint(gap_lo, gap_hi);
      if (gap_lo < z && z < gap_hi) {
        c.f = Polynomial(a_below ? 1.0 : -1.0);
        c.separator = z;
        return c;
      }
    }
    c.f.c[0] = m_lines[b].x0 - m_lines[a].x0;
    c.f.c[1] = m_lines[b].v - m_lines[a].v;
    c.f.degree = 1;
    return c;
  }
  [[nodiscard]] std::optional<OrderCertificate> order_certificate_beside(uint32_t /*kept*/,
                                                                         uint32_t /*from*/,
                                                                         uint32_t to, double now,
                                                                         float separator,
                                                                         int side) const {
    ++beside_calls;
    const auto [lo, hi] = range(to, now);
    if (!(side > 0 ? lo > separator : hi < separator)) return std::nullopt;
    ++beside_proved;
    OrderCertificate c;
    c.end = m_horizon;
    c.f = Polynomial(double(side));
    c.separator = separator;
    return c;
  }
  [[nodiscard]] double value(uint32_t a, double t) const {
    return m_lines[a].x0 + m_lines[a].v * t;
  }
  mutable int beside_calls = 0, beside_proved = 0;

 private:
  struct Line {
    double x0, v;
  };
  [[nodiscard]] std::pair<double, double> range(uint32_t a, double now) const {
    const double x = value(a, now), y = value(a, m_horizon);
    return {std::min(x, y), std::max(x, y)};
  }
  static float midpoint(double lo, double hi) { return float(0.5 * lo + 0.5 * hi); }
  double m_horizon;
  std::vector<Line> m_lines;
};
static_assert(SeparatorKeys<HorizonLineKeys>);
static_assert(!SeparatorKeys<LinearMotionKeys>);

// The hand-overs of ReplaceInPlaceIsEraseThenInsert with separators: a pair (replace_in_pair) and
// seven (replace_in_place) whose certificates of a replacement come from the separators where
// they can, against a list that erases and inserts (and computes every certificate), with the
// audit on. Most replacements are proved from a separator; the orders, the next event and the
// events stay those of erase then insert.
TEST(KineticSortLinear, ReplacementsFromSeparatorsAreEraseThenInsert) {
  for (const int size : {2, 7}) {
    HorizonLineKeys keys(21);
    TwinLists<HorizonLineKeys> lists(keys);
    std::mt19937_64 rng(size);
    std::uniform_real_distribution<double> u(-1, 1);
    std::vector<uint32_t> members;
    for (int i = 0; i < size; ++i) {
      members.push_back(keys.add(0.5 * size * u(rng), 0.1 * u(rng)));
      lists.insert(members.back());
    }
    int replacements = 0;
    for (int step = 1; step <= 400; ++step) {
      const double t = 0.05 * step;
      ASSERT_NO_FATAL_FAILURE(lists.advance_to(t));
      const size_t k = size_t(rng() % members.size());
      const uint32_t from = members[k];
      // At from's value now, mostly moving as slowly (a hand-over), now and then fast.
      const double v = (step % 5 == 0 ? 1.0 : 0.1) * u(rng);
      const uint32_t to = keys.add(keys.value(from, t) - v * t, v);
      if (size == 2) {
        lists.a.replace_in_pair(from, to, t);
        ++replacements;
      } else if (lists.a.replace_in_place(from, to, t)) {
        ++replacements;
      } else {
        lists.a.erase(from, t);
        lists.a.insert(to, t);
      }
      members[k] = to;
      ASSERT_NO_FATAL_FAILURE(lists.expect_replaced(from, to, t));
    }
    EXPECT_EQ(lists.a.stats().events(), lists.b.stats().events()) << size;
    if (size > 2) {
      EXPECT_GT(lists.a.stats().events(), 5u);  // swaps between the hand-overs
    }
    EXPECT_GT(replacements, 300) << size;
    // A pair is apart about half of the time (its separator then serves), seven mostly.
    EXPECT_GT(keys.beside_proved, size == 2 ? 80 : 300) << size;
    EXPECT_LT(keys.beside_proved, keys.beside_calls) << size;  // some fail and are computed
  }
}

// A broken order is reported as an exception naming the pair, the key values and the
// certificate (the grid adds the band, pixel and time), not an abort.
TEST(KineticSortAudit, FailureIsAnExceptionWithThePairAndTheKeyValues) {
  PolynomialKeys keys;
  const uint32_t a = keys.add(Polynomial{0.0, 1.0});  // key t
  const uint32_t b = keys.add(Polynomial{1.0});       // key 1: a before b until t = 1
  Simulator sim;
  KineticSortedList<PolynomialKeys> list(keys, sim.queue(), kOwner,
                                         KineticSortConfig{kKind, false});
  list.insert(a, 0);
  list.insert(b, 0);
  EXPECT_NO_THROW(list.audit(0.5));
  keys.set_motion(b, Polynomial{-1.0}, 0);  // moved without replace_motion: the order is stale
  try {
    list.audit(0.5);
    FAIL() << "the audit accepted a broken order";
  } catch (const KineticAuditFailure& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("pair (0, 1)"), std::string::npos) << what;
    EXPECT_NE(what.find("certificate broken"), std::string::npos) << what;
    EXPECT_NE(what.find("key values 0.5, -1"), std::string::npos) << what;
  }
}

// The same broken order through audit_problem: every sort returns the problem (to which an owner
// adds where it was found) and neither throws nor aborts; nothing when the order holds.
template <class Sort>
void expect_audit_problem_reported() {
  PolynomialKeys keys;
  const uint32_t a = keys.add(Polynomial{0.0, 1.0});  // key t
  const uint32_t b = keys.add(Polynomial{1.0});       // key 1: a before b until t = 1
  Simulator sim;
  Sort sort(keys, sim.queue(), kOwner, KineticSortConfig{kKind, false});
  sort.insert(a, 0);
  sort.insert(b, 0);
  EXPECT_EQ(sort.audit_problem(0.5), std::nullopt);
  keys.set_motion(b, Polynomial{-1.0}, 0);  // moved without replace_motion: the order is stale
  std::optional<std::string> problem;
  ASSERT_NO_THROW(problem = sort.audit_problem(0.5));
  ASSERT_TRUE(problem.has_value());
  EXPECT_NE(problem->find("pair (0, 1)"), std::string::npos) << *problem;
  EXPECT_NE(problem->find("certificate broken"), std::string::npos) << *problem;
  EXPECT_THROW(sort.audit(0.5), KineticAuditFailure);
}

TEST(KineticSortAudit, ProblemIsReturnedNotThrownByEverySort) {
  expect_audit_problem_reported<KineticSortedList<PolynomialKeys>>();
  expect_audit_problem_reported<KineticTournament<PolynomialKeys>>();
  expect_audit_problem_reported<KineticHeap<PolynomialKeys>>();
}

}  // namespace
}  // namespace kinray
