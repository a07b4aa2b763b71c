// mrqp drivers -- bus-load budget: bits and frames per control cycle against the bus capacity.
//
// A BusBudget lists the frames one bus carries per control cycle (cyclic lines) plus sporadic
// periodic frames such as heartbeats (averaged over cycles) and computes, with
// firmware_if/bus_timing.h, the bits and the time on the wire per cycle without stuffing and with
// worst-case stuffing, and the utilisation = worst-case time / cycle period. check() refuses a
// budget whose worst-case utilisation exceeds the limit (80 % by default) and says by how much;
// report() is the start-up report. Setup only (allocates).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "mrqp/firmware_if/bus_timing.h"

namespace mrqp::drivers {

enum class FrameFormat : std::uint8_t {
  Classic = 0,  ///< classic CAN data frame, 0..8 bytes
  Fd,           ///< CAN FD frame without bit-rate switch (whole frame at the nominal rate)
  FdBrs         ///< CAN FD frame with bit-rate switch (data phase at the data rate)
};

struct BusSpec {
  std::string name = "bus";
  std::uint32_t nominal_bps = 1000000;  ///< arbitration / classic rate
  std::uint32_t data_bps = 0;           ///< > 0: a CAN FD bus with this data-phase rate
  double cycle_hz = 1000.0;             ///< control cycle rate
  double limit = 0.8;                   ///< largest acceptable worst-case utilisation (0, 1]
};

/// "classic 1 Mbit/s" or "CAN FD 1/5 Mbit/s".
std::string busSpecLabel(const BusSpec& spec);

struct BudgetLine {
  std::string label;
  std::uint32_t count = 0;  ///< frames per cycle (cyclic) or per period (periodic)
  std::uint8_t len = 0;     ///< payload bytes of one frame
  FrameFormat format = FrameFormat::Classic;
  double period_s = 0.0;            ///< 0: every cycle; > 0: `count` frames every period_s (averaged)
  mrqp_fw_frame_bits bits_min{};    ///< one frame, no stuffing
  mrqp_fw_frame_bits bits_worst{};  ///< one frame, worst-case stuffing
  double ns_min = 0.0;              ///< one frame
  double ns_worst = 0.0;
  double per_cycle = 0.0;  ///< frames per cycle (count, or count x cycle period / period_s)
};

struct BudgetResult {
  bool valid = true;  ///< false: a configuration error (see error)
  std::string error;
  double cycle_ns = 0.0;
  double frames_per_cycle = 0.0;
  double nominal_bits_min = 0.0;  ///< per cycle, at the nominal rate
  double nominal_bits_worst = 0.0;
  double data_bits_min = 0.0;  ///< per cycle, at the data rate (FD with BRS)
  double data_bits_worst = 0.0;
  double time_min_ns = 0.0;  ///< per cycle on the wire
  double time_worst_ns = 0.0;
  double utilisation_min = 0.0;  ///< time / cycle period
  double utilisation_worst = 0.0;
  double limit = 0.8;
  bool fits = true;  ///< valid and utilisation_worst <= limit
};

class BusBudget {
 public:
  explicit BusBudget(BusSpec spec);

  /// `count` frames of `len` bytes every cycle.
  void addCyclic(const std::string& label, std::uint32_t count, unsigned len, FrameFormat format);
  /// `count` frames of `len` bytes every `period_s` seconds (heartbeats...), averaged per cycle.
  void addPeriodic(const std::string& label, std::uint32_t count, unsigned len, FrameFormat format,
                   double period_s);

  // The traffic of this project's devices (docs/protocol.md), per control cycle:
  void addSync();                                        ///< SYNC, 0 bytes
  void addArmDrives(std::uint32_t n, bool tpdo2);        ///< RPDO1 8 + TPDO1 8 (+ TPDO2 7) each
  void addHeartbeats(std::uint32_t n, double period_s);  ///< 1-byte heartbeats every period_s
  void addMitMotors(std::uint32_t n);                    ///< command 8 + reply 6 each
  void addHandBoard(std::uint32_t joints);               ///< FD command + feedback frames (BRS)
  void addFtClassic(std::uint32_t n);                    ///< forces 8 + moments 8 each
  void addFtFd(std::uint32_t n);                         ///< one 32-byte FD frame (BRS) each
  void addImuFd(std::uint32_t n);                        ///< one 24-byte FD frame (BRS) each

  const BusSpec& spec() const noexcept { return spec_; }
  const std::vector<BudgetLine>& lines() const noexcept { return lines_; }
  BudgetResult result() const;
  /// True if the budget fits. Otherwise false and `message` says what and by how much.
  bool check(std::string* message) const;
  /// Multi-line start-up report: one line per entry and the totals.
  std::string report() const;

 private:
  void add(const std::string& label, std::uint32_t count, unsigned len, FrameFormat format, double period_s);
  BusSpec spec_;
  std::vector<BudgetLine> lines_;
  std::string error_;
};

}  // namespace mrqp::drivers
