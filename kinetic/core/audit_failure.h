#pragma once
// What a kinetic structure's audit throws when a certificate or an order does not hold, instead
// of aborting: its owner adds where (band, pixel, time) and the program ends with one line.
#include <stdexcept>

namespace kinray {

/// A kinetic structure's audit found a certificate or an order that does not hold.
struct KineticAuditFailure : std::runtime_error {
  using std::runtime_error::runtime_error;
};

}  // namespace kinray
