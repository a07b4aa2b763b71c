// The wire scaling of impedance actuators (see actuator_scaling.hpp).
#include "loop/actuator_scaling.hpp"

#include <algorithm>
#include <cmath>

namespace mrqp::loop {

namespace {

bool usable(double x) noexcept { return std::isfinite(x) && x > 0.0; }

}  // namespace

mrqp_fw_mit_ranges mitRanges(const problem::Entity& e, int joint) noexcept {
  mrqp_fw_mit_ranges r = MRQP_FW_MIT_RANGES_DEFAULT_INIT;
  const auto k = static_cast<Eigen::Index>(joint);
  const double lo = e.qLower()(k), hi = e.qUpper()(k);
  if (std::isfinite(lo) && std::isfinite(hi) && hi > lo) {
    const double margin = 0.1 * (hi - lo);
    r.p_min = static_cast<float>(lo - margin);
    r.p_max = static_cast<float>(hi + margin);
  }
  if (usable(e.vLimit()(k))) {
    r.v_max = static_cast<float>(1.5 * e.vLimit()(k));
    r.v_min = -r.v_max;
  }
  if (usable(e.effortLimit()(k))) {
    r.t_max = static_cast<float>(1.5 * e.effortLimit()(k));
    r.t_min = -r.t_max;
  }
  return r;
}

mrqp_fw_hand_scale handScale(const problem::Entity& e, const std::vector<int>& joints) noexcept {
  mrqp_fw_hand_scale s = MRQP_FW_HAND_SCALE_DEFAULT_INIT;
  double p = 0.0, v = 0.0, t = 0.0;
  bool all_p = true, all_v = true, all_t = true;
  for (int j : joints) {
    const auto k = static_cast<Eigen::Index>(j);
    const double lo = e.qLower()(k), hi = e.qUpper()(k);
    if (std::isfinite(lo) && std::isfinite(hi) && hi > lo) {
      p = std::max({p, std::fabs(lo - 0.1 * (hi - lo)), std::fabs(hi + 0.1 * (hi - lo))});
    } else {
      all_p = false;
    }
    if (usable(e.vLimit()(k)))
      v = std::max(v, 1.5 * e.vLimit()(k));
    else
      all_v = false;
    if (usable(e.effortLimit()(k)))
      t = std::max(t, 1.5 * e.effortLimit()(k));
    else
      all_t = false;
  }
  // i16 positions (±32767 codes), i12 velocities and torques (±2047).
  if (all_p && p > 0.0) s.position_lsb = static_cast<float>(p / 32767.0);
  if (all_v && v > 0.0) s.velocity_lsb = static_cast<float>(v / 2047.0);
  if (all_t && t > 0.0) s.torque_lsb = static_cast<float>(t / 2047.0);
  return s;
}

}  // namespace mrqp::loop
