#pragma once
// What a kinetic sort sorts: keys that give the order certificate of two ids from a time on
// (KineticKeys), optionally a proof of order handed on across a replacement (SeparatorKeys) and
// exact ties at an instant (keys_tied). The models: linear_motion_keys.h, polynomial_keys.h, and
// the pixels' depth keys (kinetic/grid/pixel_depth_order.h). The conventions they follow are
// kinetic_sort.h's.
#include <concepts>
#include <cstdint>
#include <optional>

#include "kinetic/core/certificate_schedule.h"

namespace kinray {

template <class K>
concept KineticKeys = requires(const K& k, uint32_t a, uint32_t b, double t) {
  { k.order_certificate(a, b, t) } -> std::same_as<OrderCertificate>;  // t = now; valid from now on
  { k.value(a, t) } -> std::convertible_to<double>;  // the key at time t, for audit / brute force
};

/// Keys may also hand on a proof of order (OrderCertificate::separator): when `to` replaces
/// `from` in a sort (a pixel's triangle handing over to its neighbour across an edge) and the
/// certificate of `kept` and `from` carried a separator, order_certificate_beside(kept, from, to,
/// now, separator, side) returns the certificate of (kept, to) if `to` provably stays on `side` of
/// the separator (+1: after it, so kept before to; -1: before it) through the window of (kept,
/// from)'s certificate, which must be (kept, to)'s too; std::nullopt when it cannot tell, and the
/// sort computes order_certificate(kept, to, now). `kept`'s side was proved with the separator for
/// that whole window, so its motion is not looked at.
template <class K>
concept SeparatorKeys = KineticKeys<K> &&
    requires(const K& k, uint32_t a, double t, float separator, int side) {
  {
    k.order_certificate_beside(a, a, a, t, separator, side)
    } -> std::same_as<std::optional<OrderCertificate>>;
};

/// Keys may also say that two keys are equal at t although their values, evaluated in double,
/// differ beyond the audit's tolerance (`bool tied(a, b, t) const`): the audit then accepts
/// either order of that pair at t.
template <class K>
[[nodiscard]] bool keys_tied(const K& keys, uint32_t a, uint32_t b, double t) {
  if constexpr (requires { keys.tied(a, b, t); })
    return keys.tied(a, b, t);
  else
    return false;
}

}  // namespace kinray
