// A direction read from a file (a joint axis, a COLLADA <rotate> axis) brought into a range where
// its norm can be computed: x² + y² + z² overflows to infinity for components near 1e300 (and the
// "unit" vector becomes (0, 0, 0)) or underflows to zero near 1e-300. Such a vector is first
// divided by its largest |component|, so (1e300, 1e300, 1e300) normalises to (1, 1, 1)/√3; a
// vector in the safe range is left as it is (its normalisation is unchanged, bit for bit).
#pragma once

#include <cmath>

namespace mrqp::gen {

/// The divisor to apply to (x, y, z) before normalising it: 1 when its largest |component| m is
/// within [1e-100, 1e100], m otherwise, and 0 when a component is not finite or all are zero (no
/// direction).
inline double directionDivisor(double x, double y, double z) {
  if (!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(z)) return 0.0;
  const double m = std::fmax(std::fabs(x), std::fmax(std::fabs(y), std::fabs(z)));
  if (m == 0.0) return 0.0;
  return m >= 1e-100 && m <= 1e100 ? 1.0 : m;
}

}  // namespace mrqp::gen
