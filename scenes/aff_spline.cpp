#include "scenes/aff_spline.h"

#include <algorithm>
#include <cmath>

namespace kinray {
namespace {

using Quat = Eigen::Quaterniond;

// Below this sin(angle), log, exp and slerp fall back to their limits (quat.c's g_dEpsilon).
constexpr double kSmallSine = 1e-3;

Quat scaled(const Quat& q, double c) {
  return Quat(q.w() * c, q.x() * c, q.y() * c, q.z() * c);
}
Quat sum(const Quat& a, const Quat& b) {
  return Quat(a.w() + b.w(), a.x() + b.x(), a.y() + b.y(), a.z() + b.z());
}
Quat difference(const Quat& a, const Quat& b) {
  return sum(a, scaled(b, -1.0));
}

/// log of a unit quaternion: (0, angle * axis); near angle 0 the vector part as it is.
Quat quat_log(const Quat& q) {
  if (std::abs(q.w()) < 1.0) {
    const double angle = std::acos(q.w()), sine = std::sin(angle);
    if (std::abs(sine) >= kSmallSine) {
      const double c = angle / sine;
      return Quat(0, c * q.x(), c * q.y(), c * q.z());
    }
  }
  return Quat(0, q.x(), q.y(), q.z());
}

/// exp of a pure quaternion (0, angle * axis).
Quat quat_exp(const Quat& q) {
  const double angle = q.vec().norm(), sine = std::sin(angle);
  const double c = std::abs(sine) >= kSmallSine ? sine / angle : 1.0;
  return Quat(std::cos(angle), c * q.x(), c * q.y(), c * q.z());
}

Quat slerp(double t, const Quat& p, const Quat& q) {
  const double cosine = std::clamp(p.dot(q), -1.0, 1.0);
  const double angle = std::acos(cosine), sine = std::sin(angle);
  if (sine < kSmallSine) return p;
  return sum(scaled(p, std::sin((1.0 - t) * angle) / sine), scaled(q, std::sin(t * angle) / sine));
}

Quat from_axis_angle(const Eigen::Vector3d& axis, double degrees) {
  const double norm = axis.norm();
  if (norm == 0) return Quat::Identity();
  const double half = 0.5 * degrees * M_PI / 180.0;
  const Eigen::Vector3d v = std::sin(half) * axis / norm;
  return Quat(std::cos(half), v.x(), v.y(), v.z());
}

/// The outgoing (at key i1) and incoming (at key i2) tangent weights of piece i1..i2.
struct TangentWeights {
  double out0 = 0, out1 = 0, in0 = 0, in1 = 0;
};
TangentWeights tangent_weights(std::span<const SplineKey> k, size_t i0) {
  const SplineKey &a = k[i0], &b = k[i0 + 1], &c = k[i0 + 2], &d = k[i0 + 3];
  TangentWeights w;
  const double adj0 = 2 * (c.time - b.time) / (c.time - a.time);
  w.out0 = 0.5 * adj0 * (1 - b.tension) * (1 + b.continuity) * (1 + b.bias);
  w.out1 = 0.5 * adj0 * (1 - b.tension) * (1 - b.continuity) * (1 - b.bias);
  const double adj1 = 2 * (c.time - b.time) / (d.time - b.time);
  w.in0 = 0.5 * adj1 * (1 - c.tension) * (1 - c.continuity) * (1 + c.bias);
  w.in1 = 0.5 * adj1 * (1 - c.tension) * (1 + c.continuity) * (1 - c.bias);
  return w;
}

}  // namespace

PositionSpline::PositionSpline(std::span<const SplineKey> keys) {
  for (size_t i0 = 0; i0 + 3 < keys.size(); ++i0) {
    const Eigen::Vector3d &p0 = keys[i0].value, &p1 = keys[i0 + 1].value, &p2 = keys[i0 + 2].value,
                          &p3 = keys[i0 + 3].value;
    const TangentWeights w = tangent_weights(keys, i0);
    const Eigen::Vector3d dp = p2 - p1;
    const Eigen::Vector3d t_out = w.out1 * dp + w.out0 * (p1 - p0);
    const Eigen::Vector3d t_in = w.in1 * (p3 - p2) + w.in0 * dp;
    m_pieces.push_back({p1, t_out, 3 * dp - 2 * t_out - t_in, -2 * dp + t_out + t_in,
                        keys[i0 + 1].time, keys[i0 + 2].time});
  }
}

Eigen::Vector3d PositionSpline::at(double t) const {
  const auto [i, u] = locate_piece(m_pieces, t);
  const Piece& p = m_pieces[i];
  return p.c0 + u * (p.c1 + u * (p.c2 + u * p.c3));
}

RotationSpline::RotationSpline(std::span<const SplineKey> keys) {
  std::vector<Quat> q(keys.size());
  for (size_t i = 0; i < keys.size(); ++i)
    q[i] = from_axis_angle(keys[i].value, keys[i].angle_degrees);
  for (size_t i0 = 0; i0 + 3 < keys.size(); ++i0) {
    const size_t i1 = i0 + 1, i2 = i0 + 2, i3 = i0 + 3;
    // As kbsplrot.c: key i2 is flipped into the half-space of key i1 (and stays flipped for the
    // next pieces); key i3 is used as given here and flipped only when its own piece comes.
    if (q[i1].dot(q[i2]) < 0) q[i2] = scaled(q[i2], -1.0);
    const TangentWeights w = tangent_weights(keys, i0);
    const Quat log_dq = quat_log(q[i1].conjugate() * q[i2]);
    const Quat t_out =
        sum(scaled(log_dq, w.out1), scaled(quat_log(q[i0].conjugate() * q[i1]), w.out0));
    const Quat t_in =
        sum(scaled(log_dq, w.in0), scaled(quat_log(q[i2].conjugate() * q[i3]), w.in1));
    const Quat a = q[i1] * quat_exp(scaled(difference(t_out, log_dq), 0.5));
    const Quat b = q[i2] * quat_exp(scaled(difference(log_dq, t_in), 0.5));
    m_pieces.push_back({q[i1], a, b, q[i2], keys[i1].time, keys[i2].time});
  }
}

Eigen::Quaterniond RotationSpline::at(double t) const {
  const auto [i, s] = locate_piece(m_pieces, t);
  const Piece& p = m_pieces[i];
  const Quat squad = slerp(2 * s * (1 - s), slerp(s, p.p, p.q), slerp(s, p.a, p.b));
  return squad.normalized();
}

}  // namespace kinray
