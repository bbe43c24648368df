#include "kinetic/sort/sort_core.h"

#include <cmath>

namespace kinray {

namespace detail {

double value_tolerance(double va, double vb) {
  return 1e-9 * (1 + std::fabs(va) + std::fabs(vb));
}

}  // namespace detail

}  // namespace kinray
