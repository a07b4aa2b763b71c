// One item of mrqp-run's summary.json `hands` (docs/force-control.md, "Results of a run"): per
// end-effector of the scene's force_control section its mode, user force, force tracking error and
// torque-limit hits, and the JSON text of the list. Filled by HandsRecorder (hands_recorder.hpp).
#pragma once

#include <string>
#include <vector>

namespace mrqp::run {

struct HandSummary {
  std::string name;
  std::string mode;                ///< the mode at the end of the run
  double force_target_n = 0.0;     ///< fᵈ at the end of the run, N along the normal
  double force_rms_error_n = 0.0;  ///< RMS of (target − sensed) over the evaluated cycles (NaN: none)
  long torque_limit_hits = 0;   ///< loop cycles with a joint of the chain at its limit; −1 without a plant
  double target_final_n = 0.0;  ///< the admittance's target on the last cycle (QP force or fᵈ)
  double measured_final_n = 0.0;  ///< the sensed force on the last cycle
  double torque_ratio_max = 0.0;  ///< largest |τ| / τ_max of the chain over the run (NaN without a plant)
  long evaluated_cycles = 0;      ///< loop cycles in the RMS
};

/// The JSON array of `hands`, one object per end-effector (the keys above).
std::string handsJson(const std::vector<HandSummary>& hands);
/// One line per end-effector on stdout (the end-of-run text).
void printHands(const std::vector<HandSummary>& hands);

}  // namespace mrqp::run
