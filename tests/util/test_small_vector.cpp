// SmallVector against std::vector under the operations the kinetic sorted list uses: inserts and
// erases at every position, growth past the inline capacity and back, moves of inline and
// allocated contents.
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "util/small_vector.h"

namespace kinray {
namespace {

template <class A, class B>
void expect_same(const A& a, const B& b) {
  ASSERT_EQ(a.size(), b.size());
  for (size_t i = 0; i < a.size(); ++i) EXPECT_EQ(a[i], b[i]) << "at " << i;
}

TEST(SmallVector, FollowsStdVectorThroughRandomInsertsAndErases) {
  std::mt19937 rng(7);
  SmallVector<uint64_t, 2> small;
  std::vector<uint64_t> reference;
  for (int step = 0; step < 20000; ++step) {
    const bool grow = reference.size() < 2 ? true : (rng() % 100) < (reference.size() < 12 ? 55u : 40u);
    if (grow) {
      const size_t at = rng() % (reference.size() + 1);
      const uint64_t value = rng();
      small.insert(small.begin() + at, value);
      reference.insert(reference.begin() + ptrdiff_t(at), value);
    } else {
      const size_t at = rng() % reference.size();
      small.erase(small.begin() + at);
      reference.erase(reference.begin() + ptrdiff_t(at));
    }
    expect_same(small, reference);
    if (::testing::Test::HasFailure()) return;
  }
}

TEST(SmallVector, StaysInlineUpToItsCapacity) {
  SmallVector<uint32_t, 2> v;
  v.push_back(1);
  v.push_back(2);
  EXPECT_EQ(v.heap_bytes(), 0u);
  EXPECT_EQ(v.capacity(), 2u);
  v.push_back(3);
  EXPECT_GE(v.capacity(), 3u);
  EXPECT_EQ(v.heap_bytes(), v.capacity() * sizeof(uint32_t));
  v.clear();
  EXPECT_TRUE(v.empty());
  EXPECT_GE(v.capacity(), 3u);  // clear keeps the allocation, as std::vector does
}

TEST(SmallVector, MovesInlineAndAllocatedContents) {
  SmallVector<uint32_t, 2> inline_one;
  inline_one.push_back(5);
  SmallVector<uint32_t, 2> moved(std::move(inline_one));
  expect_same(moved, std::vector<uint32_t>{5});
  EXPECT_TRUE(inline_one.empty());

  SmallVector<uint32_t, 2> big;
  for (uint32_t k = 0; k < 9; ++k) big.push_back(k);
  SmallVector<uint32_t, 2> target;
  target.push_back(42);
  target = std::move(big);
  expect_same(target, std::vector<uint32_t>{0, 1, 2, 3, 4, 5, 6, 7, 8});
  EXPECT_TRUE(big.empty());
  EXPECT_EQ(big.heap_bytes(), 0u);
}

}  // namespace
}  // namespace kinray
