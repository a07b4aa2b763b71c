// The controller's cycle (docs/loop.md):
//
//   read()      poll every bus's router, each device's update(): fault report
//   estimate()  q, q̇ of every robot from its drives: on the robot's cycles the state the
//               controller predicted (integrated from its q̈) is corrected by what each joint did
//               differently from its last setpoint (the feedback is sampled at the SYNC that
//               carried it: one robot cycle old); a robot with `state: commanded` keeps its
//               integrated command (a position-controlled robot: encoders checked, not fed
//               back); floating bases, objects and mechanisms from contact kinematics
//   hooks       a fixed-capacity list of CycleHook (the estimator and the admittance plug in here)
//   update()    MultiRobotProblem::update
//   solve()     MultiRobotProblem::solve
//   write()     integrate q̈ over the period; position drives get q and q̇, torque drives τ;
//               transmit (on the robot's cycles: the loop period × its divisor)
//
// A QP that is not Optimal, a fatal driver fault, a stale sensor or a non-finite value switches
// the controller to its safe behaviour in the same cycle: the QP is no longer solved; position
// drives hold with damping (or the CiA 402 quick stop, per robot), torque drives brake; the arm
// drivers are told (ArmDriver::setSafeState: no recovery any more). Recoverable drive faults under
// the hardware section's recovery policy, the drivers' fault events and their text, and the safe
// exit after the last cycle: controller_safety.cpp.
// Every phase is timed. Set-up allocates and throws; cycle() and the boot steps do neither.
#pragma once

#include <mrqp/drivers/bus.hpp>
#include <mrqp/drivers/bus_router.hpp>
#include <mrqp/drivers/faults.hpp>

#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "loop/contact_estimator.hpp"
#include "loop/hardware_check.hpp"
#include "loop/log_ring.hpp"
#include "loop/robot_io.hpp"
#include "problem/multi_robot_problem.hpp"

namespace mrqp::drivers {
class ArmDriver;
}

namespace mrqp::loop {

class Controller;

/// A step between the estimate and the QP update (estimator, admittance). Real-time: noexcept,
/// no allocation.
class CycleHook {
 public:
  virtual void onCycle(Controller& controller, drivers::TimeNs now) noexcept = 0;

 protected:
  ~CycleHook() = default;
};

enum class CyclePhase : std::uint8_t { Read = 0, Estimate, Update, Solve, Write };
inline constexpr int kPhaseCount = 5;

enum class StopReason : std::uint8_t { None = 0, QpNotOptimal, DriverFault, StaleSensor, NonFinite };
const char* stopReasonStr(StopReason reason) noexcept;

struct ControllerOptions {
  double brake_damping = 5.0;  ///< N·m·s/rad: torque drives brake with τ = −D q̇
  /// Objects, mechanisms and floating bases from contact kinematics (else: the prediction).
  bool contact_estimation = true;
  /// Driver fault flags that stop the controller (others are logged only).
  std::uint32_t fatal_flags = 0;  ///< 0: the default set (see controller.cpp)
};

struct CycleTiming {
  std::array<drivers::TimeNs, kPhaseCount> phase_ns{};
  drivers::TimeNs total_ns = 0;
};

class Controller {
 public:
  static constexpr int kMaxHooks = 8;

  /// `buses[b]` is bus b of the hardware section (a SimNode or a SocketCanBus); they outlive it.
  Controller(problem::MultiRobotProblem& problem, const ResolvedHardware& hardware,
             const std::vector<drivers::Bus*>& buses, const ControllerOptions& options = ControllerOptions{});
  Controller(const Controller&) = delete;
  Controller& operator=(const Controller&) = delete;

  bool addHook(CycleHook& hook) noexcept;

  // ---- boot (at the loop rate, before the first cycle) ----
  void startDevices(drivers::TimeNs now) noexcept;
  /// One boot cycle: read, request enable once every device has booted, transmit. True when
  /// every device is ready (booted and enabled). The fault flags seen are OR-ed into bootFlags().
  bool bootCycle(drivers::TimeNs now) noexcept;
  std::uint32_t bootFlags() const noexcept { return boot_flags_; }

  // ---- the cycle ----
  void cycle(drivers::TimeNs now) noexcept;

  // ---- log columns: registered by attachLog (set-up), written every cycle ----
  /// Registers the columns (task and contact names by id; a missing name reads "task<id>").
  void attachLog(LogRing& log, const std::vector<std::string>& task_names = {},
                 const std::vector<std::string>& contact_names = {});
  /// Set-up, after attachLog and before the log is frozen: one more column per name, written every
  /// cycle from `values[i]` (a buffer its owner, e.g. a hook, keeps up to date and alive).
  void attachLogValues(LogRing& log, const std::vector<std::string>& names, const double* values);

  // ---- state ----
  problem::MultiRobotProblem& problem() noexcept { return problem_; }
  std::uint64_t cycles() const noexcept { return cycle_; }
  double period() const noexcept { return dt_; }
  const CycleTiming& lastTiming() const noexcept { return timing_; }
  qp::QpStatus lastStatus() const noexcept { return status_; }
  bool safeStopped() const noexcept { return stop_ != StopReason::None; }
  StopReason stopReason() const noexcept { return stop_; }
  std::uint64_t stopCycle() const noexcept { return stop_cycle_; }
  drivers::TimeNs stopTime() const noexcept { return stop_time_; }
  /// The fault flags (drivers::fault::) that stopped it, and the device ("ENTITY.JOINT" or the
  /// robot name) where it was seen first.
  std::uint32_t stopFlags() const noexcept { return stop_flags_; }
  const std::string& stopDevice() const noexcept { return stop_device_ ? *stop_device_ : no_device_; }
  /// OR of every fault flag seen since the start.
  std::uint32_t flagsSeen() const noexcept { return flags_seen_; }
  /// First time (since the start) each flag was seen, −1 if never.
  drivers::TimeNs flagFirstSeen(int bit) const noexcept { return flag_first_[static_cast<std::size_t>(bit)]; }
  const std::vector<RobotIo>& robots() const noexcept { return robots_; }
  /// The contact-kinematics estimator (nullptr when switched off).
  const ContactEstimator* estimator() const noexcept { return estimator_.get(); }
  /// Set-up notices (devices declared but not run by this build).
  const std::vector<std::string>& notices() const noexcept { return notices_; }
  std::size_t busCount() const noexcept { return routers_.size(); }
  const drivers::BusRouter& router(std::size_t b) const noexcept { return *routers_[b]; }

  // ---- safety through the drivers (controller_safety.cpp) ----
  /// A fault a driver reported, copied in the cycle that first saw it (per device or bus and flag).
  struct FaultEvent {
    drivers::TimeNs t = 0;  ///< since the first cycle
    std::uint64_t cycle = 0;
    const std::string* where = nullptr;  ///< "ENTITY.JOINT", "ENTITY.FRAME", the bus or the robot
    bool is_bus = false;
    drivers::DeviceFaults device{};
    drivers::BusFaults bus_faults{};
  };
  static constexpr std::size_t kMaxFaultEvents = 64;
  std::size_t faultEventCount() const noexcept { return event_count_; }
  const FaultEvent& faultEvent(std::size_t i) const noexcept { return events_[i]; }
  /// Events beyond kMaxFaultEvents, not kept.
  std::uint64_t faultEventsDropped() const noexcept { return events_dropped_; }
  /// The drivers' text of an event (drivers::describeDeviceFaults; allocates).
  static std::string describe(const FaultEvent& event);
  /// "DEVICE: the drivers' text" of the driver fault that stopped the controller; empty when no
  /// driver fault did (allocates).
  std::string stopDescription() const;
  /// The recovery policy is bringing drives back (every robot holds meanwhile); completed ones.
  bool recovering() const noexcept { return recovering_; }
  /// The robots hold: safe-stopped or recovering (a plant that follows the controller's q̈ stops).
  bool holding() const noexcept { return stop_ != StopReason::None || recovering_; }
  std::uint32_t recoveries() const noexcept { return recoveries_; }
  /// The safe exit after the last cycle: every arm driver's requestSafeExit (quick stop or disable
  /// voltage, then the NMT state of the hardware section's safe_exit), the other devices disabled.
  void requestSafeExit(drivers::TimeNs now) noexcept;
  /// One cycle of the safe exit (read, update, transmit per robot cycle); true once every arm
  /// driver is done and the others' disable has gone out for three robot cycles.
  bool exitCycle(drivers::TimeNs now) noexcept;
  bool exitDone() const noexcept;
  /// Fault flags seen during the safe exit.
  std::uint32_t exitFlags() const noexcept { return exit_flags_; }

 private:
  struct ReportedSlot {
    const drivers::Device* device = nullptr;
    std::size_t offset = 0;   ///< into reported_
    std::size_t devices = 0;  ///< its report's device count, then its bus count
    std::size_t buses = 0;
  };
  void initSafety(const ResolvedHardware& hw);
  const std::string* deviceName(const RobotIo& r, const drivers::Device* d, std::size_t i) const noexcept;
  const std::string* busName(const RobotIo& r, std::size_t b) const noexcept;
  bool isArm(const drivers::Device* d) const noexcept;
  void recordEvents(const RobotIo& r, const drivers::Device& d, const drivers::FaultReport& rep,
                    drivers::TimeNs now) noexcept;
  void onDeviceFaults(RobotIo& r, drivers::Device& d, const drivers::FaultReport& rep, std::uint32_t flags,
                      drivers::TimeNs now) noexcept;
  void startLoopRecovery(const FaultEvent& what, std::uint32_t flags, drivers::TimeNs now) noexcept;
  void stepLoopRecovery(drivers::TimeNs now) noexcept;
  void enterSafeState(drivers::TimeNs now) noexcept;
  /// A driven joint without fresh feedback (`flag`: kFeedbackMissing or kSampleLost): the
  /// recovery policy's for a CiA 402 drive, else a stale-sensor stop.
  void staleJoint(RobotIo& r, std::size_t joint, std::uint32_t flag, drivers::TimeNs now) noexcept;

  bool robotCycle(const RobotIo& r) const noexcept {
    return cycle_ % static_cast<std::uint64_t>(r.divisor) == 0u;
  }
  void read(drivers::TimeNs now) noexcept;
  void estimate(drivers::TimeNs now) noexcept;
  void write(drivers::TimeNs now) noexcept;
  void writeSafe(drivers::TimeNs now) noexcept;
  void remember(RobotIo& r, std::size_t joint) noexcept;
  void trip(StopReason reason, std::uint32_t flags, const std::string* device, drivers::TimeNs now) noexcept;
  void logRow(drivers::TimeNs now) noexcept;

  problem::MultiRobotProblem& problem_;
  ControllerOptions options_;
  double dt_;
  std::uint32_t fatal_;
  int feedback_missing_cycles_;
  // Frame loss (hardware section's frame_loss): robot cycles averaged (exponentially) for the rate
  // of missing feedback, and the largest rate accepted (a drive losing more is a stale sensor).
  double loss_window_, loss_limit_;
  std::vector<std::unique_ptr<drivers::BusRouter>> routers_;
  std::vector<RobotIo> robots_;
  std::vector<std::uint8_t> commanded_;  ///< per robot: state: commanded (no feedback correction)
  std::vector<std::uint8_t> interpolating_;  ///< per robot: interpolating_drives
  std::unique_ptr<ContactEstimator> estimator_;
  std::array<CycleHook*, kMaxHooks> hooks_{};
  int hook_count_ = 0;
  std::uint64_t cycle_ = 0;
  drivers::TimeNs start_ = 0;
  bool started_ = false;
  bool enable_requested_ = false;
  std::uint64_t boot_cycle_ = 0;
  std::vector<std::string> notices_;
  std::uint32_t boot_flags_ = 0;
  CycleTiming timing_;
  qp::QpStatus status_ = qp::QpStatus::Optimal;
  StopReason stop_ = StopReason::None;
  std::uint64_t stop_cycle_ = 0;
  drivers::TimeNs stop_time_ = -1;
  std::uint32_t stop_flags_ = 0;
  const std::string* stop_device_ = nullptr;
  std::string no_device_;
  // safety (controller_safety.cpp)
  RecoverySpec recovery_;
  std::vector<drivers::ArmDriver*> arms_;
  std::vector<std::string> bus_names_;  ///< per bus of the hardware section
  std::vector<ReportedSlot> reported_slots_;
  std::vector<std::uint32_t> reported_;  ///< flags already recorded, per device / bus of each report
  std::array<FaultEvent, kMaxFaultEvents> events_{};
  std::size_t event_count_ = 0;
  std::uint64_t events_dropped_ = 0;
  FaultEvent stop_event_{};
  bool stop_event_set_ = false;
  bool recovering_ = false;
  FaultEvent recovery_event_{};
  std::uint32_t recovery_flags_ = 0;
  int recovery_attempts_ = 0;
  drivers::TimeNs recovery_next_ = 0;
  std::uint32_t recoveries_ = 0;
  bool exiting_ = false;
  std::uint64_t exit_cycle_ = 0;
  std::uint32_t exit_flags_ = 0;
  std::uint32_t flags_seen_ = 0;
  std::array<drivers::TimeNs, 32> flag_first_{};

  // log
  LogRing* log_ = nullptr;
  int col_t_ = -1, col_phase_ = -1, col_total_ = -1, col_status_ = -1, col_iter_ = -1, col_safe_ = -1,
      col_flags_ = -1;
  int col_tasks_ = -1, col_contacts_ = -1, col_joints_ = -1, col_buses_ = -1, col_ft_ = -1;
  std::vector<int> task_ids_, contact_ids_;
  struct LogValues {
    int first = -1, count = 0;
    const double* values = nullptr;
  };
  std::vector<LogValues> log_values_;
  std::vector<std::uint64_t> bus_frames_prev_;
};

}  // namespace mrqp::loop
