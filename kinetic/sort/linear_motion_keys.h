#pragma once
// The simplest key model of the kinetic sorts: keys moving linearly in time.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "kinetic/core/certificate_schedule.h"
#include "kinetic/sort/sort_keys.h"

namespace kinray {

/// Keys moving linearly: key_i(t) = x_i + v_i t (absolute time, certificate origin 0).
/// Motion can be replaced (set_velocity / set_motion) keeping the same origin convention.
class LinearMotionKeys {
 public:
  uint32_t add(double x0, double v) {
    m_lines.push_back({x0, v});
    return static_cast<uint32_t>(m_lines.size() - 1);
  }
  /// From now on key(t) = x0 + v t (x0 is the value at time 0 of the new line); then call
  /// replace_motion(id, now) on the structures holding id.
  void set_motion(uint32_t id, double x0, double v) { m_lines[id] = {x0, v}; }
  [[nodiscard]] size_t size() const { return m_lines.size(); }
  [[nodiscard]] OrderCertificate order_certificate(uint32_t a, uint32_t b, double /*t*/) const {
    const Line& la = m_lines[a];
    const Line& lb = m_lines[b];
    OrderCertificate c;
    c.f.c[0] = lb.x0 - la.x0;
    c.f.c[1] = lb.v - la.v;
    c.f.degree = 1;
    return c;
  }
  [[nodiscard]] double value(uint32_t a, double t) const {
    return m_lines[a].x0 + m_lines[a].v * t;
  }

 private:
  struct Line {
    double x0, v;  // interleaved: one cache line access per object
  };
  std::vector<Line> m_lines;
};

static_assert(KineticKeys<LinearMotionKeys>);

}  // namespace kinray
