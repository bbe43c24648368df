#include <gtest/gtest.h>

#include "kinetic/grid/row_crossings.h"

namespace kinray {
namespace {

// Two row patterns have equal keys iff they give every row of the band the same sign: every
// slot of bands of 1 to 6 rows, every pair of signs (the inconsistent ones too).
TEST(RowCrossings, RowStepKeysAreEqualIffThePatternsAreTheSameFunction) {
  int equal = 0, different = 0;
  for (int count = 1; count <= 6; ++count)
    for (int sa = 0; sa < count; ++sa)
      for (int sb = 0; sb < count; ++sb)
        for (int la : {-1, 1})
          for (int ha : {-1, 1})
            for (int lb : {-1, 1})
              for (int hb : {-1, 1}) {
                bool same = true;
                for (int q = 0; q < count; ++q) same &= (q < sa ? la : ha) == (q < sb ? lb : hb);
                const bool keys =
                    detail::row_step(sa, la, ha, count) == detail::row_step(sb, lb, hb, count);
                ASSERT_EQ(keys, same) << "count " << count << " slots " << sa << ", " << sb
                                      << " signs " << la << ha << ", " << lb << hb;
                ++(same ? equal : different);
              }
  EXPECT_GT(equal, 100);
  EXPECT_GT(different, 100);
}

}  // namespace
}  // namespace kinray
