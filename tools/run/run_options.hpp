// mrqp-run's command line (docs/loop.md).
#pragma once

#include <string>
#include <vector>

#include "loop/fault_injector.hpp"

namespace mrqp::run {

struct RunOptions {
  std::string scene;
  std::string out;
  std::string plant;               ///< "" = from the scene (ideal when it says nothing)
  std::vector<std::string> buses;  ///< empty = sim
  long cycles = -1;
  double duration = -1.0;
  bool realtime = false;
  bool paced = false;  ///< cycles paced at the period without the real-time set-up
  bool cycle_clock = false;  ///< --clock cycles: the drivers' time is cycles run × period (SocketCAN)
  double pace = 1.0;         ///< --pace F (with --clock cycles): F periods of wall time per cycle
  bool quiet = false;
  bool plots = true;
  bool force_control = true;  ///< false: --no-force-control, every admittance in mode off
  std::vector<loop::FaultRequest> faults;
  std::vector<std::string> sets;
};

/// Parses argv; on a usage error throws std::invalid_argument with the message. `help` is set for
/// -h/--help.
RunOptions parseRunOptions(int argc, char** argv, bool* help);

const char* runUsage() noexcept;

/// The value of option `opt` as a number; std::invalid_argument "OPT: expected a number, got 'V'".
double optionNumber(const std::string& opt, const std::string& v);
/// "IF[,IF...]" as a list of interface names; an empty name is an error naming `opt`.
std::vector<std::string> interfaceList(const std::string& opt, const std::string& v);

}  // namespace mrqp::run
