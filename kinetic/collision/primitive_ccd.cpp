// Floating-point filters in front of the exact decision. The first two only ever say "no
// contact", and only when the rounding error of the doubles cannot change the answer; the
// interval decision also certifies contacts; the rest is decided in rationals.
#include "kinetic/collision/primitive_ccd.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <mutex>
#include <optional>
#include <utility>

#include "kinetic/collision/exact_ccd.h"
#include "kinetic/collision/interval_ccd.h"
#include "kinetic/core/interval_arithmetic.h"
#include "util/check.h"
#include "util/parallel.h"

namespace kinray {
namespace {

/// Points [0, first_points) belong to the first primitive (the vertex, or edge a).
int first_points(ContactType type) {
  return type == ContactType::vertex_face ? 1 : 2;
}

/// True when on some axis the extents of the two primitives' points do not overlap;
/// extent(i, axis) gives point i's {lo, hi} on that axis.
template <class Extent>
bool extents_separated(ContactType type, Extent&& extent) {
  const int first_end = first_points(type);
  for (int axis = 0; axis < 3; ++axis) {
    double lo[2] = {std::numeric_limits<double>::infinity(),
                    std::numeric_limits<double>::infinity()};
    double hi[2] = {-lo[0], -lo[0]};
    for (int i = 0; i < 4; ++i) {
      const int side = i < first_end ? 0 : 1;
      const auto [point_lo, point_hi] = extent(i, axis);
      lo[side] = std::min(lo[side], point_lo);
      hi[side] = std::max(hi[side], point_hi);
    }
    if (hi[0] < lo[1] || hi[1] < lo[0]) return true;
  }
  return false;
}

/// Over a window: each coordinate start + u (end - start), u in [lo, hi], enclosed in interval
/// arithmetic (the difference rounded, hence enclosed too).
bool window_boxes_separated(ContactType type, const PrimitiveMotion& m, LocalWindow window) {
  using detail::Interval;
  const Interval u = {window.lo, window.hi};
  return extents_separated(type, [&](int i, int axis) {
    const Interval x =
        Interval::point(m.start[i][axis]) + u * Interval::around(m.end[i][axis] - m.start[i][axis]);
    return std::pair{x.lo, x.hi};
  });
}

/// Linear motion stays inside the box of its start and end positions; min and max are exact.
bool swept_boxes_separated(ContactType type, const PrimitiveMotion& m) {
  return extents_separated(type, [&](int i, int axis) {
    return std::minmax(m.start[i][axis], m.end[i][axis]);
  });
}

}  // namespace

std::vector<double> contact_times(ContactType type, const PrimitiveMotion& motion,
                                  PrimitiveCcdCounters* counters, LocalWindow window) {
  PrimitiveCcdCounters local;
  PrimitiveCcdCounters& count = counters ? *counters : local;
  ++count.tests;
  for (int i = 0; i < 4; ++i)
    KINRAY_CHECK_MSG(motion.start[i].allFinite() && motion.end[i].allFinite(),
                     "primitive CCD needs finite coordinates");
  KINRAY_CHECK_MSG(0 <= window.lo && window.lo <= window.hi && window.hi <= 1,
                   "primitive CCD window outside [0, 1]");
  if (swept_boxes_separated(type, motion) ||
      (!window.whole() && window_boxes_separated(type, motion, window))) {
    ++count.box_rejections;
    return {};
  }
  // The coplanarity cubic's Bernstein coefficients on [0, 1] of one certain sign: no contact.
  // They are the interval decision's first piece too, when the window is the whole segment.
  const detail::CoplanarityCubic whole(motion, 0, 1);
  if (whole.certainly_nonzero()) {
    ++count.cubic_rejections;
    return {};
  }
  const detail::BernsteinBound<3> cubic =
      window.whole() ? whole.bound()
                     : detail::CoplanarityCubic(motion, window.lo, window.hi).bound();
  IntervalCcdCounters interval;
  std::optional<std::vector<double>> certified =
      interval_contact_times(type, motion, interval, window, cubic);
  count.interval_rejections += interval.rejections;
  count.interval_contacts += interval.contacts;
  count.exact_signs += interval.exact_signs;
  if (certified) {
    count.contacts += !certified->empty();
    return *std::move(certified);
  }
  ++count.exact_decisions;
  std::vector<double> times = exact_contact_times(type, to_rational(motion), window);
  count.contacts += !times.empty();
  return times;
}

std::vector<std::optional<double>> first_contact_times(std::span<const PrimitiveQuery> queries,
                                                       PrimitiveCcdCounters* counters,
                                                       const PrimitiveCcdBatchConfig& config) {
  std::vector<std::optional<double>> first(queries.size());
  std::mutex sum;
  // Blocks of consecutive pairs, handed out one at a time: most pairs cost a few hundred
  // nanoseconds and a few near-degenerate ones a thousand times more, so equal shares per thread
  // would leave one thread with the rational decisions. A block's counters are summed once.
  const size_t threads = size_t(resolve_threads(config.threads));
  const size_t block = std::max<size_t>(1, queries.size() / (8 * threads));
  const size_t blocks = (queries.size() + block - 1) / block;
  parallel_for_dynamic(blocks, config.threads, [&](size_t b) {
    PrimitiveCcdCounters count;
    for (size_t i = b * block; i < std::min(queries.size(), (b + 1) * block); ++i) {
      const std::vector<double> times = contact_times(queries[i].type, queries[i].motion, &count);
      if (!times.empty()) first[i] = times.front();
    }
    if (counters) {
      const std::lock_guard lock(sum);
      *counters += count;
    }
  });
  return first;
}

Eigen::Vector3d contact_point(ContactType type, const PrimitiveMotion& motion, double t) {
  const std::array<Eigen::Vector3d, 4> p = motion.at(t);
  if (type == ContactType::vertex_face) return p[0];
  // Closest points of two segments (Ericson, Real-Time Collision Detection, 5.1.9).
  const Eigen::Vector3d d1 = p[1] - p[0], d2 = p[3] - p[2], r = p[0] - p[2];
  const double a = d1.squaredNorm(), e = d2.squaredNorm(), f = d2.dot(r);
  double s = 0, u = 0;
  if (a <= 0 && e <= 0) return 0.5 * (p[0] + p[2]);
  if (a <= 0) {
    u = std::clamp(f / e, 0.0, 1.0);
  } else {
    const double c = d1.dot(r);
    if (e <= 0) {
      s = std::clamp(-c / a, 0.0, 1.0);
    } else {
      const double b = d1.dot(d2), denom = a * e - b * b;
      s = denom > 0 ? std::clamp((b * f - c * e) / denom, 0.0, 1.0) : 0.0;
      u = (b * s + f) / e;
      if (u < 0) {
        u = 0;
        s = std::clamp(-c / a, 0.0, 1.0);
      } else if (u > 1) {
        u = 1;
        s = std::clamp((b - c) / a, 0.0, 1.0);
      }
    }
  }
  return 0.5 * ((p[0] + s * d1) + (p[2] + u * d2));
}

}  // namespace kinray
