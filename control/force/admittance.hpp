// The force admittance of one end-effector (Sec. III, eq. 45–46, Fig. 4; docs/force-control.md),
// along the contact normal n, one sample per robot cycle:
//
//   v  = K_I (f_target − ⟨f_sensor | n⟩)             eq. 45, the scalar along n
//   v_c = min(max(v_min, v), v_max)                  eq. 46, a guarded motion
//   ṽ  = Butterworth₃(v_c)                           3rd order, cutoff f_c at the robot's rate
//
// Displacement bound (a workspace / penetration bound, not in the paper): the end-effector's
// displacement s along n (the integral of ṽ, given to step()) stays within ±d_max. The clamp of
// eq. 46 narrows as s nears a bound, v_c ≤ (d_max − s)/T_b and v_c ≥ (−d_max − s)/T_b with
// T_b = 3 (2/ω_c + 1/f_s) (three times the filter's delay at DC plus one sample), so the filtered
// velocity comes to rest at the bound without a jump in v_c: a target the end-effector cannot
// reach (an infeasible fᵈ, a sensor that reads nothing) no longer drives the reference away.
//
// ṽ n is the reference velocity of the end-effector's task (the position reference is its
// integral, the acceleration reference its derivative: AdmittanceHook). Hold: while the sensor
// is stale or faulted (or the mode is off) the filter is fed zero instead of v_c, so ṽ ramps to
// zero through the filter and nothing accumulates however long the fault lasts (no wind-up); the
// filter's state is never reset, so a change of target, of mode or the end of a hold moves ṽ
// continuously (bumpless). Set-up checks the parameters; step() is noexcept and allocation-free.
#pragma once

#include "force/butterworth_lowpass.hpp"

namespace mrqp::force {

struct AdmittanceGains {
  double gain = 5.0e-4;     ///< K_I, m s⁻¹ N⁻¹ (the paper's value)
  double v_min = -0.05;     ///< m/s
  double v_max = 0.05;      ///< m/s
  double cutoff_hz = 20.0;  ///< the low-pass's cutoff
  /// d_max, m: the largest displacement along n either way (the scene's max_displacement).
  double max_displacement = 0.1;
};

class Admittance {
 public:
  /// Why these gains cannot run at `sample_hz` (the robot's rate), or nullptr when they can.
  static const char* check(const AdmittanceGains& gains, double sample_hz) noexcept;

  /// Throws std::invalid_argument with check()'s reason. Set-up.
  Admittance(const AdmittanceGains& gains, double sample_hz);

  /// One sample: the filtered velocity ṽ along n (m/s). `f_target` and `f_measured` are the
  /// target and the sensed force along n (N); `sensor_ok` false holds; `displacement` is the
  /// end-effector's displacement s along n so far (m, the integral of the velocities returned),
  /// which the bound keeps within ±max_displacement.
  double step(double f_target, double f_measured, bool sensor_ok, double displacement = 0.0) noexcept;

  /// T_b, s: the time constant with which v_c is brought to zero at a bound.
  double brakingTime() const noexcept { return braking_time_; }

  double velocity() const noexcept { return filter_.output(); }
  /// v_c of the last sample (0 while holding).
  double clamped() const noexcept { return clamped_; }
  bool holding() const noexcept { return holding_; }
  const AdmittanceGains& gains() const noexcept { return gains_; }
  const ButterworthLowPass3& filter() const noexcept { return filter_; }

 private:
  AdmittanceGains gains_;
  ButterworthLowPass3 filter_;
  double clamped_ = 0.0;
  double braking_time_ = 0.0;
  bool holding_ = false;
};

}  // namespace mrqp::force
