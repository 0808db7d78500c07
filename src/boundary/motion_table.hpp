#pragma once
// A body's motion read from a table of times and values (a CSV of t, x, y(, z), angle), interpolated by
// natural cubic splines, so that velocity and acceleration are continuous (the wall condition takes
// both). A natural spline's acceleration is zero at the first and last rows. Before the first time and
// after the last the values hold still.
#include <algorithm>
#include <vector>

namespace sph {

class CubicSpline {
 public:
  CubicSpline() = default;
  // t strictly increasing, at least two points.
  CubicSpline(std::vector<double> t, std::vector<double> y) : t_(std::move(t)), y_(std::move(y)), m_(t_.size(), 0.0) {
    const std::size_t n = t_.size();
    if (n < 3) return;  // linear: second derivatives zero
    // Natural spline: m_0 = m_{n-1} = 0, the tridiagonal system for the inner second derivatives.
    std::vector<double> c(n, 0.0), d(n, 0.0);
    for (std::size_t i = 1; i + 1 < n; ++i) {
      const double h0 = t_[i] - t_[i - 1], h1 = t_[i + 1] - t_[i];
      const double a = h0, b = 2.0 * (h0 + h1), cc = h1;
      const double r = 6.0 * ((y_[i + 1] - y_[i]) / h1 - (y_[i] - y_[i - 1]) / h0);
      const double denom = b - a * c[i - 1];
      c[i] = cc / denom, d[i] = (r - a * d[i - 1]) / denom;
    }
    for (std::size_t i = n - 2; i >= 1; --i) m_[i] = d[i] - c[i] * m_[i + 1];
  }

  // The value (order 0), its first or second derivative at s; held constant outside [t_0, t_end].
  double operator()(double s, int order = 0) const {
    if (t_.empty()) return 0.0;
    if (s <= t_.front()) return order == 0 ? y_.front() : 0.0;
    if (s >= t_.back()) return order == 0 ? y_.back() : 0.0;
    const std::size_t k = static_cast<std::size_t>(std::upper_bound(t_.begin(), t_.end(), s) - t_.begin()) - 1;
    const double h = t_[k + 1] - t_[k], a = (t_[k + 1] - s) / h, b = (s - t_[k]) / h;
    if (order == 0)
      return a * y_[k] + b * y_[k + 1] + ((a * a * a - a) * m_[k] + (b * b * b - b) * m_[k + 1]) * h * h / 6.0;
    if (order == 1)
      return (y_[k + 1] - y_[k]) / h + ((1.0 - 3.0 * a * a) * m_[k] + (3.0 * b * b - 1.0) * m_[k + 1]) * h / 6.0;
    return a * m_[k] + b * m_[k + 1];
  }
  double first_time() const { return t_.empty() ? 0.0 : t_.front(); }
  const std::vector<double>& times() const { return t_; }

 private:
  std::vector<double> t_, y_, m_;  // m_: second derivatives at the knots
};

}  // namespace sph
