// mrqp-drive-emu -- the drive side of the CiA 402 arm protocol for a set of node ids, with a
// simple physical model per joint and fault injection (docs: tools/drive_emu/README.md).
//
// DriveEmulator is transport-free: frames in via onFrame(), time moves via advance(), frames out
// through a FrameSink. Each node is the drive side of mrqp drivers (EmulatedCia402Drive: NMT,
// SDO server, CiA 402 state machine, PDOs) with a joint model behind it. emu_sim.hpp attaches the
// emulator to a SimNode (tests), main.cpp to SocketCAN.
#pragma once

#include <mrqp/firmware_if/firmware_if.h>
#include <mrqp/drivers/time.hpp>
#include <mrqp/emulation/emulated_cia402_drive.hpp>

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace mrqp::drive_emu {

using mrqp::drivers::TimeNs;

constexpr TimeNs kNever = mrqp::emulation::EmulatedCia402Drive::kNever;

struct JointModel {
  double inertia = 0.05;          ///< kg m^2, > 0
  double damping = 0.05;          ///< N m s/rad, >= 0
  double torque_limit = 20.0;     ///< N m, > 0 (motor saturation)
  double kp = 200.0;              ///< CSP position loop inside the drive, N m/rad
  double kd = 5.0;                ///< N m s/rad
  double initial_position = 0.0;  ///< rad
};

struct NodeFaults {
  TimeNs heartbeat_stop_at = kNever;  ///< stop producing the heartbeat at this time
  TimeNs emcy_at = kNever;            ///< raise an EMCY (and go to Fault) at this time
  std::uint16_t emcy_code = 0x2310;   ///< continuous over-current
  TimeNs saturate_at = kNever;        ///< from this time the motor torque is stuck at +torque_limit
};

struct EmuNode {
  std::uint8_t node = 1;
  mrqp_fw_arm_scale scale = MRQP_FW_ARM_SCALE_DEFAULT_INIT;
  JointModel joint;
  NodeFaults faults;
};

struct EmuConfig {
  std::vector<EmuNode> nodes;
  std::string interface = "vcan0";
  TimeNs step = 500000;           ///< physics integration step (ns)
  TimeNs boot_delay = 2000000;    ///< reset -> boot-up message
  double drop_fraction = 0.0;     ///< of the frames the emulator sends, dropped
  double corrupt_fraction = 0.0;  ///< of the frames the emulator sends, truncated to 1 byte
  std::uint32_t seed = 1;
  double duration_s = 0.0;  ///< 0: run until signalled
  /// How strict every emulated drive is (YAML `profile`: lenient, strict, or a map of switches).
  mrqp::emulation::VendorProfile profile = mrqp::emulation::VendorProfile::lenient();
};

/// Limits of the configuration (checked by loadConfig and validateConfig).
namespace limits {
inline constexpr double kStepMsMin = 0.01;  ///< physics step
inline constexpr double kStepMsMax = 100.0;
inline constexpr double kBootDelayMsMax = 60000.0;      ///< reset -> boot-up
inline constexpr double kTimeSMax = 1.0e6;              ///< duration and fault times (s), about 11.6 days
inline constexpr double kRatedTorqueMax = 4294967.295;  ///< N m: 0x6076 is u32 mN m
inline constexpr double kRatedTorqueMin = 0.001;        ///< N m: at least 1 mN m
inline constexpr double kPhysicalMax = 1.0e6;           ///< inertia, damping, torque limit
inline constexpr double kGainMax = 1.0e9;               ///< kp, kd
inline constexpr double kPositionMax = 1000.0;          ///< |initial_position| in rad
}  // namespace limits

/// Loads a YAML configuration; on error returns false and "FILE:LINE: FIELD: message" (nothing
/// thrown, whatever the file holds).
bool loadConfig(const std::string& path, EmuConfig* config, std::string* error);
/// Parses "N@T" / "N@T:code" (T in seconds, 0..limits::kTimeSMax) fault switches of the command
/// line into `config`.
bool applyFaultSwitch(const std::string& kind, const std::string& arg, EmuConfig* config, std::string* error);
/// Validates the configuration (node ids unique 1..127, every value finite and within limits::),
/// e.g. after command-line overrides.
bool validateConfig(const EmuConfig& config, const std::string& origin, std::string* error);
/// What the configuration emulates, one line per node and the profile (for --check).
std::string describeConfig(const EmuConfig& config);

class FrameSink {
 public:
  virtual void emit(const mrqp_fw_frame& frame, TimeNs now) noexcept = 0;

 protected:
  ~FrameSink() = default;
};

struct EmuStats {
  std::uint64_t sent = 0;
  std::uint64_t dropped = 0;
  std::uint64_t corrupted = 0;
  std::uint64_t syncs = 0;
  std::uint64_t rpdos = 0;
};

class DriveEmulator {
 public:
  DriveEmulator(const EmuConfig& config, FrameSink& sink);
  ~DriveEmulator();
  DriveEmulator(const DriveEmulator&) = delete;
  DriveEmulator& operator=(const DriveEmulator&) = delete;

  /// A frame received at `now` (call advance(now) first).
  void onFrame(const mrqp_fw_frame& frame, TimeNs now) noexcept;
  /// Runs physics steps, heartbeats, boots and scheduled faults up to `now`.
  void advance(TimeNs now) noexcept;
  /// The next time advance() has something to do.
  TimeNs nextEvent() const noexcept;

  struct Drive;
  std::size_t size() const noexcept;
  double position(std::size_t i) const noexcept;  ///< rad, physical model
  mrqp_fw_cia402_state state(std::size_t i) const noexcept;
  mrqp_fw_nmt_state nmt(std::size_t i) const noexcept;
  unsigned commErrors(std::size_t i) const noexcept;  ///< SYNC timeouts of drive i
  const EmuStats& stats() const noexcept { return stats_; }

 private:
  void send(const mrqp_fw_frame& f, TimeNs now) noexcept;
  void step(Drive& d, double dt) noexcept;
  double rand01() noexcept;

  EmuConfig cfg_;
  FrameSink& sink_;
  std::vector<std::unique_ptr<Drive>> drives_;
  TimeNs next_step_ = 0;
  std::uint64_t rng_ = 1;
  EmuStats stats_{};
};

}  // namespace mrqp::drive_emu
