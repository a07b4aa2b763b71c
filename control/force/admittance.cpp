// The force admittance of one end-effector (see admittance.hpp).
#include "force/admittance.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace mrqp::force {

const char* Admittance::check(const AdmittanceGains& g, double sample_hz) noexcept {
  if (!std::isfinite(g.gain) || !(g.gain > 0.0)) return "the gain K_I must be a finite number > 0";
  if (!std::isfinite(g.v_min) || !std::isfinite(g.v_max) || !(g.v_min <= 0.0) || !(g.v_max >= 0.0) ||
      !(g.v_max > g.v_min)) {
    return "the velocity limits must be finite with v_min <= 0 <= v_max and v_min < v_max";
  }
  if (!std::isfinite(sample_hz) || !(sample_hz > 0.0)) return "the sample rate must be a finite number > 0";
  if (!std::isfinite(g.cutoff_hz) || !(g.cutoff_hz > 0.0) || !(g.cutoff_hz < 0.5 * sample_hz)) {
    return "the cutoff must be > 0 and below half the robot's sample rate (Nyquist)";
  }
  if (!std::isfinite(g.max_displacement) || !(g.max_displacement > 0.0))
    return "the displacement bound must be a finite number > 0";
  return nullptr;
}

Admittance::Admittance(const AdmittanceGains& gains, double sample_hz) : gains_(gains) {
  if (const char* why = check(gains, sample_hz)) throw std::invalid_argument(why);
  filter_.design(gains.cutoff_hz, sample_hz);
  constexpr double kPi = 3.14159265358979323846;
  braking_time_ = 3.0 * (2.0 / (2.0 * kPi * gains.cutoff_hz) + 1.0 / sample_hz);
}

double Admittance::step(double f_target, double f_measured, bool sensor_ok, double displacement) noexcept {
  const double v = gains_.gain * (f_target - f_measured);  // eq. 45 along n
  holding_ = !sensor_ok || !std::isfinite(v) || !std::isfinite(displacement);
  // eq. 46, narrowed near the displacement bound (continuous in the displacement: no jump).
  const double d_max = gains_.max_displacement;
  const double hi = std::min(gains_.v_max, std::max(0.0, (d_max - displacement) / braking_time_));
  const double lo = std::max(gains_.v_min, std::min(0.0, (-d_max - displacement) / braking_time_));
  clamped_ = holding_ ? 0.0 : std::min(std::max(lo, v), hi);
  filter_.filter(clamped_);
  // A hold decays towards zero for ever: end it exactly there (no denormals on the cycle).
  if (holding_ && filter_.quiet(1e-15)) filter_.reset(0.0);
  return filter_.output();
}

}  // namespace mrqp::force
