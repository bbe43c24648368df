#include "kinetic/core/root_finding.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <limits>

#include "kinetic/core/binomial.h"
#include "kinetic/core/double_steps.h"
#include "util/check.h"

// Root isolation in the Bernstein basis (Descartes' rule of signs, de Casteljau subdivision; see
// Lane & Riesenfeld 1981, Mourrain, Rouillier & Roy 2005), with a running error bound on every
// Bernstein coefficient so that the "no root" decision of the fast path is certified, then
// Illinois / bisection refinement on Horner's evaluation of f itself, so that the reported time
// satisfies sign_after(f, r) < 0 exactly as the callers will evaluate it.

namespace kinray {

namespace {

constexpr int kN = kMaxPolynomialDegree;
constexpr double kUnitRoundoff = 0x1p-53;
constexpr double kInf = std::numeric_limits<double>::infinity();
// Beyond this the Bernstein conversion of a normalised degree-8 polynomial could overflow; the
// rest of (s_now, infinity) is searched through s = 1 / w.
constexpr double kTailStart = 0x1p100;

thread_local RootStats t_stats;

using detail::bit_midpoint;
using detail::first_negative_near;
using detail::next_down;
using detail::next_up;

int sign_of(double x) { return (x > 0) - (x < 0); }

using detail::kBinomial;

// kRatio[n][i][j] = C(i, j) / C(n, j): power (in u on [0,1]) to Bernstein conversion.
struct RatioTable {
  std::array<std::array<std::array<double, kN + 1>, kN + 1>, kN + 1> r{};
  constexpr RatioTable() {
    for (int n = 0; n <= kN; ++n)
      for (int i = 0; i <= n; ++i)
        for (int j = 0; j <= i; ++j) r[n][i][j] = kBinomial[i][j] / kBinomial[n][j];
  }
};
constexpr RatioTable kRatio;

// Bernstein coefficients of p on [a, a + w] and a bound on the absolute error of each.
struct Bernstein {
  std::array<double, kN + 1> b{}, e{};
  int n = 0;
};

// p is trimmed (p.c[p.degree] != 0) and normalised (max |c| around 1).
void convert(const Polynomial& p, double a, double w, Bernstein& out) {
  const int n = p.degree;
  std::array<double, kN + 1> g = p.c, m{};
  for (int k = 0; k <= n; ++k) m[k] = std::fabs(g[k]);
  const double aa = std::fabs(a);
  for (int i = 0; i < n; ++i)
    for (int k = n - 1; k >= i; --k) {
      g[k] += a * g[k + 1];
      m[k] += aa * m[k + 1];
    }
  double pw = 1;
  for (int j = 1; j <= n; ++j) {
    pw *= w;
    g[j] *= pw;
    m[j] *= pw;
  }
  // Rounding count along any path: shift 2n, powers n + 1, conversion n + 3; doubled margin
  // covers the rounding of the magnitudes themselves.
  const double gamma = (8.0 * n + 16.0) * kUnitRoundoff;
  out.n = n;
  const auto& r = kRatio.r[n];
  for (int i = 0; i <= n; ++i) {
    double s = 0, ms = 0;
    for (int j = 0; j <= i; ++j) {
      s += r[i][j] * g[j];
      ms += r[i][j] * m[j];
    }
    out.b[i] = s;
    out.e[i] = ms * gamma;
  }
}

enum class LeafKind { kDefinite, kRoot, kUnresolved, kSplit };

struct Classification {
  LeafKind kind = LeafKind::kSplit;
  int first_sign = 0, last_sign = 0;  // certain signs at the two ends (kDefinite, kRoot)
};

Classification classify(const Bernstein& bz) {
  const int n = bz.n;
  int certain_count = 0;
  std::array<int, kN + 1> sg{};
  for (int i = 0; i <= n; ++i) {
    sg[i] = std::fabs(bz.b[i]) > bz.e[i] ? sign_of(bz.b[i]) : 0;
    certain_count += sg[i] != 0;
  }
  Classification c;
  // Noise level: |f| <= max|b| + max e on the leaf, no more than a few error bounds anywhere, so
  // subdividing further cannot reveal a certain sign (this stops the fuzzy edges of the noise
  // band around a multiple root from being cut to ulp size).
  double max_b = 0, max_e = 0;
  for (int i = 0; i <= n; ++i) {
    max_b = std::max(max_b, std::fabs(bz.b[i]));
    max_e = std::max(max_e, bz.e[i]);
  }
  if (certain_count == 0 || max_b <= 4 * max_e) {
    c.kind = LeafKind::kUnresolved;
    return c;
  }
  // Largest number of sign variations over all choices of the uncertain signs (Descartes' bound).
  constexpr int kNone = -1000;
  int best_pos = kNone, best_neg = kNone;
  for (int i = 0; i <= n; ++i) {
    const int from_pos = best_pos, from_neg = best_neg;
    const int start = i == 0 ? 0 : kNone;
    int np = std::max({start, from_pos, from_neg + 1});
    int nn = std::max({start, from_neg, from_pos + 1});
    if (sg[i] > 0) nn = kNone;
    if (sg[i] < 0) np = kNone;
    best_pos = np;
    best_neg = nn;
  }
  const int vmax = std::max(best_pos, best_neg);
  c.first_sign = sg[0];
  c.last_sign = sg[n];
  if (vmax == 0) {
    c.kind = LeafKind::kDefinite;
  } else if (vmax == 1 && sg[0] != 0 && sg[n] != 0 && sg[0] != sg[n]) {
    c.kind = LeafKind::kRoot;
  }
  return c;
}

// r in (lo, hi] with sign_after(f, r) == sigma, where sign_after(f, hi) == sigma is given and
// sign_after(f, lo) is presumably -sigma. Illinois steps (regula falsi halving the function value
// of an endpoint kept twice in a row); when three steps did not halve the bracket, one bisection
// step, at the arithmetic midpoint, every fourth one in bit space (so that brackets spanning many
// binades, e.g. [0, 1] around 1e-300, also end in O(64) steps). Ends on adjacent doubles.
double refine(const Polynomial& f, double lo, double hi, int sigma) {
  double flo = f(lo), fhi = f(hi);
  int kept = 0;  // +1: lo kept by the last step, -1: hi kept
  int steps_in_window = 0, bisections = 0;
  double window_width = hi - lo;
  while (next_up(lo) < hi) {
    ++t_stats.refinements;
    const double width = hi - lo;
    const bool secant_ok = std::isfinite(flo) && std::isfinite(fhi) && sign_of(flo) == -sigma &&
                           sign_of(fhi) == sigma;
    double m = 0;
    bool bisect = !secant_ok;
    if (++steps_in_window > 3) {
      steps_in_window = 0;
      bisect |= width > 0.5 * window_width;
      window_width = width;
    }
    if (!bisect) {
      m = hi - fhi * (width / (fhi - flo));
      // A secant point within two ulps of an end is moved to two ulps inside: once one end has
      // converged, this closes the bracket from that side instead of bisecting the other.
      const double in_lo = next_up(next_up(lo));
      const double in_hi = next_down(next_down(hi));
      if (in_lo < in_hi) m = std::clamp(m, in_lo, in_hi);
      bisect = !(m > lo && m < hi);
    }
    if (bisect) {
      m = (++bisections % 4 == 0) ? bit_midpoint(lo, hi) : lo + 0.5 * width;
      if (!(m > lo && m < hi)) m = bit_midpoint(lo, hi);
    }
    const double fm = f(m);
    int sm = sign_of(fm);
    if (sm == 0) sm = sign_after(f, m);
    // An exact zero keeps the secant usable with the smallest value of the side's sign.
    const double fv = fm != 0 ? fm : sm * std::numeric_limits<double>::min();
    if (sm == sigma) {
      hi = m;
      fhi = fv;
      if (kept == 1) flo *= 0.5;
      kept = 1;
    } else {
      lo = m;
      flo = fv;
      if (kept == -1) fhi *= 0.5;
      kept = -1;
    }
  }
  return hi;
}

// Tracks the sign of f along increasing s from observations (point, certain sign) and refines
// a crossing when the sign changes.
struct Walker {
  Walker(const Polynomial& poly, int start_sign, double start, bool stop)
      : f(poly), current(start_sign), last(start), stop_at_first(stop) {}
  const Polynomial& f;
  int current = 0;
  double last = 0;  // last point at which `current` was observed
  bool stop_at_first = true;
  std::vector<double>* out = nullptr;
  bool done = false;
  bool noise = false;  // a stretch passed over unsettled (first_failure's `noise`)
  std::optional<double> first;

  // Observation: f has (certain) sign sigma at p; fallback points q1, q2 (later than p, inside
  // the same leaf) are tried when Horner's evaluation at p disagrees.
  void observe(double p, int sigma, double q1, double q2) {
    if (done || sigma == 0) return;
    if (sigma == current) {
      last = std::max(last, p);
      return;
    }
    double hi = kInf;
    for (double q : {p, q1, q2}) {
      if (q > last && std::isfinite(q) && sign_after(f, q) == sigma) {
        hi = q;
        break;
      }
    }
    if (hi == kInf) {
      noise = true;
      return;
    }
    const double r = refine(f, last, hi, sigma);
    if (out) out->push_back(r);
    if (!first) first = r;
    current = sigma;
    last = hi;
    if (stop_at_first) done = true;
  }
};

struct Interval {
  double lo, hi;
  int depth;
};

// Left-to-right isolation of p on [x0, x1] (finite, x0 < x1); leaves are mapped to observations
// of f. When `reversed`, p(w) = w^n f(1/w) and x is w: leaves are visited right to left, and a
// leaf [w0, w1] is the s-interval [1/w1, 1/w0].
void isolate(const Polynomial& p, double x0, double x1, bool reversed, Walker& walker) {
  Interval stack[256];
  int top = 0;
  stack[top++] = {x0, x1, 0};
  Bernstein bz;
  while (top > 0 && !walker.done) {
    const Interval iv = stack[--top];
    convert(p, iv.lo, iv.hi - iv.lo, bz);
    Classification c = classify(bz);
    const double mid = iv.lo + 0.5 * (iv.hi - iv.lo);
    if (c.kind == LeafKind::kSplit) {
      const bool too_small = !(iv.lo < mid && mid < iv.hi) ||
                             iv.hi - iv.lo <= 8 * std::max(std::fabs(iv.lo), std::fabs(iv.hi)) *
                                                  kUnitRoundoff ||
                             iv.depth >= 200 || top + 2 > 256;
      if (!too_small) {
        ++t_stats.subdivisions;
        if (!reversed) {
          stack[top++] = {mid, iv.hi, iv.depth + 1};
          stack[top++] = {iv.lo, mid, iv.depth + 1};
        } else {
          stack[top++] = {iv.lo, mid, iv.depth + 1};
          stack[top++] = {mid, iv.hi, iv.depth + 1};
        }
        continue;
      }
      c.kind = LeafKind::kUnresolved;
    }
    if (c.kind == LeafKind::kUnresolved) {
      walker.noise = true;
      continue;
    }
    // Observation points in increasing s.
    double s_first, s_mid, s_last;
    int sign_first, sign_last;
    if (!reversed) {
      s_first = iv.lo, s_mid = mid, s_last = iv.hi;
      sign_first = c.first_sign, sign_last = c.last_sign;
    } else {
      s_first = iv.hi > 0 ? 1 / iv.hi : kInf;
      s_mid = 1 / mid;
      s_last = iv.lo > 0 ? 1 / iv.lo : kInf;
      sign_first = c.last_sign, sign_last = c.first_sign;
    }
    if (c.kind == LeafKind::kDefinite) {
      walker.observe(s_first, sign_first, s_mid, s_last);
      walker.observe(s_mid, sign_first, s_last, s_last);
    } else {
      walker.observe(s_first, sign_first, s_first, s_first);
    }
    walker.observe(s_last, sign_last, s_last, s_last);
  }
}

// Fujiwara's bound on the moduli of the roots of the trimmed polynomial p.
double root_bound(const Polynomial& p) {
  const int n = p.degree;
  const double lead = std::fabs(p.c[n]);
  double bound = 0;
  for (int k = 1; k <= n; ++k) {
    double q = std::fabs(p.c[n - k]) / lead;
    if (k == n) q *= 0.5;
    if (q == 0) continue;
    bound = std::max(bound, k == 1 ? q : std::pow(q, 1.0 / k));
  }
  return 2 * bound * (1 + 1e-6) + std::numeric_limits<double>::min();
}

// f trimmed and scaled by a power of two so that max |c| is in [1, 2).
Polynomial normalised(const Polynomial& f) {
  Polynomial p = f.trimmed();
  double mx = 0;
  for (int k = 0; k <= p.degree; ++k) mx = std::max(mx, std::fabs(p.c[k]));
  int e = 0;
  std::frexp(mx, &e);
  for (int k = 0; k <= p.degree; ++k) p.c[k] = std::ldexp(p.c[k], 1 - e);
  return p;
}

// Walks (s0, s1] (s1 may be +inf): main part in s, far part through s = 1 / w.
// Returns true when the fast path (one conversion, definitely of the current sign) decided.
bool walk(const Polynomial& f, double s0, double s1, Walker& walker) {
  const Polynomial p = normalised(f);
  // A finite end within the direct range needs no root bound (saves the pow calls); otherwise
  // Fujiwara's bound makes the search finite.
  const double reach = std::isfinite(s1) && s1 <= kTailStart ? s1 : std::min(s1, root_bound(p));
  if (s0 >= reach) return false;
  const double main_end = std::min(reach, std::max(kTailStart, s0));
  if (s0 < main_end) {
    // Fast path: one conversion on the whole main part.
    Bernstein bz;
    convert(p, s0, main_end - s0, bz);
    const Classification c = classify(bz);
    if (c.kind == LeafKind::kDefinite && c.first_sign == walker.current && main_end == reach)
      return true;
    isolate(p, s0, main_end, false, walker);
  }
  if (walker.done || main_end >= reach) return false;
  Polynomial rev;
  rev.degree = p.degree;
  for (int k = 0; k <= p.degree; ++k) rev.c[p.degree - k] = p.c[k];
  const double w0 = std::isfinite(reach) ? 1 / reach : 0.0;
  const double w1 = 1 / main_end;
  if (w0 < w1) isolate(normalised(rev), w0, w1, true, walker);
  return false;
}

// Degree 1 (after trimming): Horner's value fl(c0 + fl(c1 s)) is monotone in s, so the answer
// is the smallest double r > s_now with fl(f(r)) <= 0.
std::optional<double> first_failure_linear(double c0, double c1, double s_now, double s_end) {
  if (c1 > 0) return std::nullopt;
  auto neg = [&](double s) { return c0 + c1 * s <= 0; };
  const bool bounded = std::isfinite(s_end);
  if (bounded && !neg(s_end)) return std::nullopt;
  const double top = bounded ? s_end : std::numeric_limits<double>::max();
  if (!neg(top)) return std::nullopt;
  // Start at the rounded root and gallop to a bracket [lo, hi] of adjacent or nearby doubles
  // (neg(top) holds, so the gallop always ends there at the latest).
  double g = -c0 / c1;
  if (!(g > s_now)) g = next_up(s_now);
  if (!(g < top)) g = top;
  const double step = std::max(std::fabs(g), std::numeric_limits<double>::min()) * kUnitRoundoff;
  return first_negative_near(neg, g, s_now, top, step, std::numeric_limits<int>::max(),
                             &t_stats.refinements)
      .value_or(top);
}

}  // namespace

RootStats& root_stats() { return t_stats; }

int sign_after_root(const Polynomial& f, double s) {
  const Polynomial g = shifted(f, s);  // g.c[k] = f^(k)(s) / k!
  for (int k = 1; k <= g.degree; ++k)
    if (g.c[k] != 0) return sign_of(g.c[k]);
  return 0;
}

std::optional<double> first_failure(const Polynomial& f, double s_now, double s_end) {
  bool noise = false;
  return first_failure(f, s_now, s_end, noise);
}

std::optional<double> first_failure(const Polynomial& f, double s_now, double s_end, bool& noise) {
  ++t_stats.calls;
  noise = false;
  KINRAY_DCHECK(std::isfinite(s_now) && !std::isnan(s_end));
  const int n = f.effective_degree();
  if (n <= 1) {
    // Horner's value c0 + c1 s, as operator() and sign_after compute it.
    const double c0 = f.c[0], c1 = n == 1 ? f.c[1] : 0.0;
    if (n == 1 && linear_holds_through(c0, c1, s_now, s_end)) {
      ++t_stats.fast_path_no_root;
      return std::nullopt;
    }
    const double v = n == 1 ? c0 + c1 * s_now : c0;
    const int now_sign = v != 0 ? sign_of(v) : sign_of(c1);
    if (now_sign == 0) return std::nullopt;  // zero polynomial
    if (now_sign < 0) return s_now;
    std::optional<double> r;
    if (n == 1 && s_end > s_now) r = first_failure_linear(c0, c1, s_now, s_end);
    if (!r) ++t_stats.fast_path_no_root;
    return r;
  }
  const int now_sign = sign_after(f, s_now);
  if (now_sign < 0) return s_now;
  if (!(s_end > s_now)) return std::nullopt;
  Walker walker(f, 1, s_now, true);
  if (walk(f, s_now, s_end, walker)) {
    ++t_stats.fast_path_no_root;
    return std::nullopt;
  }
  if (!walker.done && std::isfinite(s_end)) {
    const int end_sign = sign_after(f, s_end);
    walker.observe(s_end, end_sign, s_end, s_end);
  }
  noise = walker.noise;
  return walker.first;
}

std::vector<double> sign_changes(const Polynomial& f, double s0, double s1) {
  std::vector<double> out;
  const int start = sign_after(f, s0);
  if (start == 0 || !(s1 > s0)) return out;
  Walker walker(f, start, s0, false);
  walker.out = &out;
  walk(f, s0, s1, walker);
  if (std::isfinite(s1)) walker.observe(s1, sign_after(f, s1), s1, s1);
  return out;
}

}  // namespace kinray
