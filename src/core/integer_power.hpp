#pragma once
#include <cmath>

namespace sph {

// x^n for a small exponent n >= 0 by repeated squaring, cheaper than std::pow in the shifting loop and
// the Tait equation of state (docs/performance.md, "Design measurements").
inline double integer_power(double x, int n) {
  double result = 1.0;
  for (; n > 0; n >>= 1, x *= x)
    if (n & 1) result *= x;
  return result;
}

// x^e, by repeated squaring when e is a whole number up to 32 (the Tait exponents 7 and 3).
inline double power(double x, double e) {
  return e >= 0.0 && e <= 32.0 && e == std::floor(e) ? integer_power(x, static_cast<int>(e)) : std::pow(x, e);
}

}  // namespace sph
