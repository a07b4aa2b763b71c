// mrqp-stream's command line (README.md, "mrqp-stream") and the arm driver's configuration it
// asks for (nodes and scales from a mrqp-drive-emu YAML file or --nodes, timeouts, exit policy).
#pragma once

#include <mrqp/drivers/arm_driver.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace mrqp::stream {

struct Options {
  std::string interface = "vcan0";
  std::vector<std::uint8_t> nodes;
  double rate = 250.0;
  long cycles = 2000;
  std::string yaml;
  double amplitude = 0.2;         ///< rad
  double frequency = 0.5;         ///< Hz
  double max_error = 0.1;         ///< rad, tracking error bound
  int expect_heartbeat_loss = 0;  ///< node whose heartbeat loss is expected (and required)
  int heartbeat_timeout_ms = 250;
  int sdo_timeout_ms = 100;  ///< per SDO request during boot (a slow emulated target needs more)
  int heartbeat_ms = 100;
  int feedback_missing_cycles = 5;
  bool quiet = false;
  bool realtime = false;  ///< loop::setupRealtime before the first cycle
  bool recover = false;   ///< RecoveryPolicy::Automatic
  bool tpdo_rtr_allowed = false;
  long comm_cycle_us = 0;  ///< 0x1006; 0: the cycle period
  drivers::ExitStop exit_stop = drivers::ExitStop::QuickStop;
  drivers::ExitNmt exit_nmt = drivers::ExitNmt::PreOperational;
  unsigned long device_type = 0, vendor_id = 0, product_code = 0;
};

/// Parses the command line into `o`. Returns -1 to go on, else the exit status (0 after --help,
/// 2 after an error, with its message on stderr).
int parseOptions(int argc, char** argv, Options* o);

/// The arm driver's configuration of the options; false (message in `err`) for a bad YAML file.
bool armConfig(Options& o, drivers::ArmConfig* cfg, std::string* err);

}  // namespace mrqp::stream
