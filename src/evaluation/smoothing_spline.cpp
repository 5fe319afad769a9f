// Cubic smoothing spline: Reinsch's pentadiagonal system solved by banded LDLᵀ, exact |f| integrals and extremes.
#include "stiffpath/evaluation/smoothing_spline.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <limits>
#include <numbers>
#include <numeric>

#include "stiffpath/core/error.hpp"

namespace stiffpath::evaluation {

namespace {

// Solves the symmetric pentadiagonal system (diag d, first off-diagonal e, second f) in place of b.
void solve_pentadiagonal(std::vector<double> d, std::vector<double> e, std::vector<double> f, std::vector<double>& b) {
  const std::size_t m = d.size();
  std::vector<double> l1(m, 0.0), l2(m, 0.0);
  for (std::size_t r = 0; r < m; ++r) {
    if (r >= 1) d[r] -= l1[r - 1] * l1[r - 1] * d[r - 1];
    if (r >= 2) d[r] -= l2[r - 2] * l2[r - 2] * d[r - 2];
    if (r + 1 < m) l1[r] = (e[r] - (r >= 1 ? l2[r - 1] * l1[r - 1] * d[r - 1] : 0.0)) / d[r];
    if (r + 2 < m) l2[r] = f[r] / d[r];
  }
  for (std::size_t r = 0; r < m; ++r) {
    if (r >= 1) b[r] -= l1[r - 1] * b[r - 1];
    if (r >= 2) b[r] -= l2[r - 2] * b[r - 2];
  }
  for (std::size_t r = 0; r < m; ++r) b[r] /= d[r];
  for (std::size_t r = m; r-- > 0;) {
    if (r + 1 < m) b[r] -= l1[r] * b[r + 1];
    if (r + 2 < m) b[r] -= l2[r] * b[r + 2];
  }
}

double simpson(double fa, double fm, double fb, double width) { return width * (fa + 4.0 * fm + fb) / 6.0; }

}  // namespace

SmoothingSpline SmoothingSpline::fit(std::span<const double> t, std::span<const double> y, double cutoff_wavelength,
                                     std::span<const double> weights) {
  if (t.size() != y.size() || (!weights.empty() && weights.size() != t.size())) {
    throw Error(fmt::format("smoothing spline: {} parameters, {} values, {} weights", t.size(), y.size(), weights.size()));
  }
  if (t.empty()) throw Error("smoothing spline: no points to fit");
  if (!std::isfinite(cutoff_wavelength) || cutoff_wavelength < 0.0) {
    throw Error(fmt::format("smoothing spline: cutoff wavelength must be finite and >= 0, got {}", cutoff_wavelength));
  }
  for (std::size_t i = 0; i < t.size(); ++i) {
    const double w = weights.empty() ? 1.0 : weights[i];
    if (!std::isfinite(t[i]) || !std::isfinite(y[i]) || !std::isfinite(w) || w <= 0.0) {
      throw Error(fmt::format("smoothing spline: point {} (t = {}, y = {}, weight {}) is not usable", i, t[i], y[i], w));
    }
  }
  std::vector<std::size_t> order(t.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return t[a] < t[b]; });
  const double range = t[order.back()] - t[order.front()];
  const double merge_eps = 1e-9 * range;

  // Merge points closer than merge_eps: weighted mean value, summed weight.
  std::vector<double> tk, yk, wk;
  for (const std::size_t i : order) {
    const double w = weights.empty() ? 1.0 : weights[i];
    if (!tk.empty() && t[i] - tk.back() <= merge_eps) {
      yk.back() = (yk.back() * wk.back() + y[i] * w) / (wk.back() + w);
      wk.back() += w;
    } else {
      tk.push_back(t[i]);
      yk.push_back(y[i]);
      wk.push_back(w);
    }
  }

  SmoothingSpline spline;
  const std::size_t n = tk.size();
  spline.t0_ = tk.front();
  spline.scale_ = n > 1 ? range / static_cast<double>(n - 1) : 1.0;
  spline.s_.resize(n);
  for (std::size_t i = 0; i < n; ++i) spline.s_[i] = (tk[i] - spline.t0_) / spline.scale_;
  spline.g_ = yk;
  spline.gamma_.assign(n, 0.0);
  if (n < 3) return spline;

  const double mean_w = std::accumulate(wk.begin(), wk.end(), 0.0) / static_cast<double>(n);
  const double omega_c = cutoff_wavelength > 0.0 ? 2.0 * std::numbers::pi * spline.scale_ / cutoff_wavelength : 0.0;
  const double alpha = cutoff_wavelength > 0.0 ? mean_w / std::pow(omega_c, 4) : 0.0;
  spline.penalty_ = alpha * std::pow(spline.scale_, 3);  // ∫f''(t)²dt = scale⁻³ ∫f''(s)²ds

  const auto& s = spline.s_;
  std::vector<double> h(n - 1);
  for (std::size_t i = 0; i + 1 < n; ++i) h[i] = s[i + 1] - s[i];
  const std::size_t m = n - 2;  // interior knots k = r + 1
  std::vector<double> d(m), e(m, 0.0), f(m, 0.0), rhs(m);
  auto inv_w = [&](std::size_t i) { return 1.0 / wk[i]; };
  for (std::size_t r = 0; r < m; ++r) {
    const std::size_t k = r + 1;
    const double a = 1.0 / h[k - 1], c = 1.0 / h[k], b = -a - c;  // column k of Q: rows k−1, k, k+1
    d[r] = (h[k - 1] + h[k]) / 3.0 + alpha * (a * a * inv_w(k - 1) + b * b * inv_w(k) + c * c * inv_w(k + 1));
    if (r + 1 < m) {
      const double b_next = -1.0 / h[k] - 1.0 / h[k + 1];
      e[r] = h[k] / 6.0 + alpha * (b * c * inv_w(k) + c * b_next * inv_w(k + 1));
    }
    if (r + 2 < m) f[r] = alpha * c * (1.0 / h[k + 1]) * inv_w(k + 1);
    rhs[r] = (yk[k + 1] - yk[k]) * c - (yk[k] - yk[k - 1]) * a;
  }
  solve_pentadiagonal(std::move(d), std::move(e), std::move(f), rhs);
  for (std::size_t r = 0; r < m; ++r) spline.gamma_[r + 1] = rhs[r];
  if (alpha > 0.0) {
    const auto& gm = spline.gamma_;
    for (std::size_t i = 0; i < n; ++i) {
      double q_gamma = 0.0;
      if (i + 1 < n) q_gamma += (gm[i + 1] - gm[i]) / h[i];
      if (i >= 1) q_gamma -= (gm[i] - gm[i - 1]) / h[i - 1];
      spline.g_[i] = yk[i] - alpha * inv_w(i) * q_gamma;
    }
  }
  return spline;
}

SmoothingSpline::Cubic SmoothingSpline::piece(std::size_t i) const {
  if (s_.size() == 1) return {g_[0], 0.0, 0.0, 0.0};
  const double h = s_[i + 1] - s_[i];
  return {g_[i], (g_[i + 1] - g_[i]) / h - h * (2.0 * gamma_[i] + gamma_[i + 1]) / 6.0, gamma_[i] / 2.0,
          (gamma_[i + 1] - gamma_[i]) / (6.0 * h)};
}

std::size_t SmoothingSpline::interval(double s) const {
  if (s_.size() < 2) return 0;
  const auto it = std::upper_bound(s_.begin(), s_.end(), s);
  const auto idx = static_cast<std::size_t>(std::max<std::ptrdiff_t>(it - s_.begin() - 1, 0));
  return std::min(idx, s_.size() - 2);
}

double SmoothingSpline::value(double t) const {
  const double s = (t - t0_) / scale_;
  if (s_.size() == 1) return g_[0];
  if (s <= s_.front()) return g_.front() + (s - s_.front()) * piece(0).c1;
  const std::size_t last = s_.size() - 2;
  if (s >= s_.back()) return g_.back() + (s - s_.back()) * piece(last).derivative(s_.back() - s_[last]);
  const std::size_t i = interval(s);
  return piece(i)(s - s_[i]);
}

double SmoothingSpline::slope(double t) const {
  if (s_.size() == 1) return 0.0;
  const double s = std::clamp((t - t0_) / scale_, s_.front(), s_.back());
  const std::size_t i = interval(s);
  return piece(i).derivative(s - s_[i]) / scale_;
}

// Calls visit(cubic, u0, u1, s_base) for the parts of each piece inside [a, b]; s = s_base + u (scaled units).
template <class Visit>
void SmoothingSpline::for_each_piece(double a, double b, Visit&& visit) const {
  const double sa = std::max((a - t0_) / scale_, s_.front()), sb = std::min((b - t0_) / scale_, s_.back());
  if (!(sb > sa) || s_.size() < 2) return;
  for (std::size_t i = interval(sa); i + 1 < s_.size(); ++i) {
    const double lo = std::max(sa, s_[i]) - s_[i], hi = std::min(sb, s_[i + 1]) - s_[i];
    if (hi > lo) visit(piece(i), lo, hi, s_[i]);
    if (s_[i + 1] >= sb) break;
  }
}

double SmoothingSpline::integral_abs(double a, double b) const {
  if (s_.size() == 1) return 0.0;
  double total = 0.0;
  for_each_piece(a, b, [&](const Cubic& c, double u0, double u1, double) {
    // Locate sign changes on a fine grid, refine each root by bisection, integrate each part by
    // Simpson's rule (exact for a cubic).
    constexpr int kGrid = 8;
    double left = u0, f_left = c(u0);
    for (int k = 1; k <= kGrid; ++k) {
      const double right = u0 + (u1 - u0) * k / kGrid, f_right = c(right);
      if ((f_left < 0.0 && f_right > 0.0) || (f_left > 0.0 && f_right < 0.0)) {
        double lo = left, hi = right;
        for (int it = 0; it < 60 && hi - lo > 1e-15 * (1.0 + std::abs(hi)); ++it) {
          const double mid = 0.5 * (lo + hi);
          ((c(mid) < 0.0) == (f_left < 0.0) ? lo : hi) = mid;
        }
        const double root = 0.5 * (lo + hi);
        total += std::abs(simpson(f_left, c(0.5 * (left + root)), 0.0, root - left));
        total += std::abs(simpson(0.0, c(0.5 * (root + right)), f_right, right - root));
      } else {
        total += std::abs(simpson(f_left, c(0.5 * (left + right)), f_right, right - left));
      }
      left = right;
      f_left = f_right;
    }
  });
  return total * scale_;
}

SplineExtremes SmoothingSpline::extremes(double a, double b) const {
  SplineExtremes ex;
  bool first = true;
  auto consider = [&](double s_abs, double v) {
    if (first || v < ex.min) ex.min = v;
    if (first || v > ex.max) ex.max = v;
    if (first || std::abs(v) > ex.max_abs) {
      ex.max_abs = std::abs(v);
      ex.t_at_max_abs = t0_ + scale_ * s_abs;
    }
    first = false;
  };
  const double ta = std::clamp(a, front(), back()), tb = std::clamp(b, front(), back());
  consider((ta - t0_) / scale_, value(ta));
  consider((tb - t0_) / scale_, value(tb));
  for_each_piece(a, b, [&](const Cubic& c, double u0, double u1, double s_base) {
    // Stationary points: c1 + 2·c2·u + 3·c3·u² = 0.
    const double qa = 3.0 * c.c3, qb = 2.0 * c.c2, qc = c.c1;
    double roots[2];
    int count = 0;
    if (std::abs(qa) < 1e-300) {
      if (std::abs(qb) > 1e-300) roots[count++] = -qc / qb;
    } else {
      const double disc = qb * qb - 4.0 * qa * qc;
      if (disc >= 0.0) {
        const double q = -0.5 * (qb + std::copysign(std::sqrt(disc), qb));
        roots[count++] = q / qa;
        if (q != 0.0) roots[count++] = qc / q;
      }
    }
    for (int k = 0; k < count; ++k) {
      if (roots[k] > u0 && roots[k] < u1) consider(s_base + roots[k], c(roots[k]));
    }
    consider(s_base + u1, c(u1));
  });
  return ex;
}

}  // namespace stiffpath::evaluation
