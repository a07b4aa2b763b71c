// Fault injection for runs on the emulated rig (docs/loop.md, "Faults"): each fault KIND@SECONDS[:DEVICE] is
// resolved at set-up against the hardware section and injected at its time where such a fault
// happens — in the emulated firmware (heartbeat-loss, frame-loss, corrupt-frames, nan-feedback,
// stale-ft), on the bus (bus-off: the controller's node meets a burst of bit errors) — never in the
// controller (a DEVICE that is a joint of an MIT motor or a hand board: heartbeat-loss, which
// those protocols do not have, silences the firmware; corrupt-frames corrupts its replies;
// nan-feedback raises its fault); `infeasible` adds to the problem a joint inequality that no acceleration within the
// joint limits can satisfy. Detection and safe-state times are read back from the controller.
#pragma once

#include <string>
#include <vector>

#include "loop/controller.hpp"
#include "loop/emulated_rig.hpp"

namespace mrqp::loop {

struct FaultRequest {
  std::string
      kind;  ///< heartbeat-loss, bus-off, frame-loss, corrupt-frames, nan-feedback, stale-ft, infeasible
  double at_s = 0.0;   ///< s since the first cycle
  std::string device;  ///< empty: the first device the fault applies to
};

/// Parses KIND@SECONDS[:DEVICE]; throws std::invalid_argument naming the problem.
FaultRequest parseFaultRequest(const std::string& spec);

struct FaultRecord {
  std::string kind;
  std::string device;
  double at_s = 0.0;
  double injected_at_s = -1.0;
  double detected_at_s = -1.0;
  double safe_state_at_s = -1.0;
};

class FaultInjector {
 public:
  /// Throws std::invalid_argument for a fault this configuration cannot have.
  FaultInjector(const std::vector<FaultRequest>& requests, EmulatedRig* rig, Controller& controller,
                const ResolvedHardware& hw);
  /// Injects the faults due at simulated time t (s since the start of the loop).
  void beforeCycle(double t, drivers::TimeNs now) noexcept;
  /// Reads detection and safe state back from the controller.
  void afterCycle() noexcept;
  const std::vector<FaultRecord>& records() const noexcept { return records_; }

 private:
  struct Target {
    PlantCia402Drive* drive = nullptr;
    PlantFtSensor* ft = nullptr;
    emulation::EmulatedMitMotor* mit = nullptr;     ///< an MIT motor's joint (heartbeat-loss: silent)
    emulation::EmulatedHandBoard* board = nullptr;  ///< a hand board's joint (heartbeat-loss: silent)
    int bus = -1;
    int robot = -1;
    int joint = -1;
  };
  EmulatedRig* rig_;
  Controller& controller_;
  std::vector<FaultRecord> records_;
  std::vector<Target> targets_;
};

}  // namespace mrqp::loop
