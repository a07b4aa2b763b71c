// summary.json's `hands` (see hand_summary.hpp).
#include "hand_summary.hpp"
#include "summary_fields.hpp"

#include <cmath>
#include <cstdio>

namespace mrqp::run {

std::string handsJson(const std::vector<HandSummary>& hands) {
  std::string out = "[";
  for (std::size_t i = 0; i < hands.size(); ++i) {
    const HandSummary& h = hands[i];
    out += std::string(i ? "," : "") + "\n    {\"name\": " + jsonString(h.name) +
           ", \"mode\": " + jsonString(h.mode) + ", \"force_target_n\": " + jsonNumber(h.force_target_n) +
           ", \"force_rms_error_n\": " + jsonNumber(h.force_rms_error_n) +
           ", \"torque_limit_hits\": " + std::to_string(h.torque_limit_hits) +
           ",\n     \"target_final_n\": " + jsonNumber(h.target_final_n) +
           ", \"measured_final_n\": " + jsonNumber(h.measured_final_n) +
           ", \"torque_ratio_max\": " + jsonNumber(h.torque_ratio_max) +
           ", \"evaluated_cycles\": " + std::to_string(h.evaluated_cycles) + "}";
  }
  return out + (hands.empty() ? "]" : "\n  ]");
}

void printHands(const std::vector<HandSummary>& hands) {
  for (const HandSummary& h : hands) {
    std::printf(
        "  force %s (%s): f^d %.3g N, final target %.3g N, sensed %.3g N, rms error %.3g N, "
        "torque-limit cycles %ld, largest |tau|/tau_max %.3g\n",
        h.name.c_str(), h.mode.c_str(), h.force_target_n, h.target_final_n, h.measured_final_n,
        h.force_rms_error_n, h.torque_limit_hits, h.torque_ratio_max);
  }
}

}  // namespace mrqp::run
