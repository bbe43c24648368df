#include "kinetic/core/simulator.h"

#include <limits>

namespace kinray {

double Simulator::next_event_time() const {
  return m_queue.empty() ? std::numeric_limits<double>::infinity() : m_queue.top_key().time;
}

}  // namespace kinray
