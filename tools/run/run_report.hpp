// mrqp-run's results: summary.json (docs/loop.md, "summary.json") and the PNG plots of a run
// (gnuplot over the log).
#pragma once

#include <limits>
#include <map>
#include <string>
#include <vector>

#include "loop/fault_injector.hpp"

namespace mrqp::run {

struct RunSummary {
  std::string scene;
  long cycles = 0;
  double period_s = 0.0;
  long deadline_misses = 0;
  long allocations_in_loop = 0;
  long log_records_dropped = 0;
  double median_us = 0.0, p99_us = 0.0, p999_us = 0.0, max_us = 0.0;
  std::string safe_stop;  ///< empty: null
  std::vector<std::pair<std::string, double>> task_errors_final;
  std::vector<std::pair<std::string, double>> joint_tracking_error_max_rad;
  std::vector<std::pair<std::string, double>> base_estimate_error_m;
  std::vector<std::pair<std::string, double>> bus_load;
  std::vector<loop::FaultRecord> faults;
  /// The drivers' text (drivers::describeDeviceFaults): of the fault that stopped the controller
  /// ("DEVICE: text", empty: none), of every fault event of the run ("t = … s (cycle …) DEVICE:
  /// text"), and per injected fault the events on its device from its injection on.
  std::string safe_stop_driver;
  std::vector<std::string> fault_events;
  std::vector<std::string> fault_driver_text;
  /// The safe exit after the last cycle (docs/loop.md, "Safety").
  bool safe_exit_done = false;
  long safe_exit_cycles = 0;
  /// Collision pairs (docs/collision.md): smallest distance over the run, measured on the plant's
  /// state, and the smallest security distance δs; NaN (left out of the file) without collisions.
  double min_distance_m = std::numeric_limits<double>::quiet_NaN();
  double delta_s_m = std::numeric_limits<double>::quiet_NaN();
  std::vector<std::pair<std::string, std::string>> extra_fields;  ///< a scene's own: name → JSON value text
};

/// Percentile p (0..1) of sorted values (nearest rank).
double percentile(const std::vector<double>& sorted, double p);

/// Writes summary.json; false when it cannot be written.
bool writeSummaryJson(const RunSummary& s, const std::string& path);
/// DIR/faults.log: the fault events of the run, one per line, with the drivers' text.
bool writeFaultLog(const RunSummary& s, const std::string& path);
/// The end-of-run text on stdout.
void printSummary(const RunSummary& s);

/// The PNG plots of a run from DIR/log.csv: task errors, contact forces, command vs feedback,
/// cycle-time histogram. Returns the files written; `error` says what failed.
std::vector<std::string> writePlots(const std::string& dir, const std::vector<std::string>& columns,
                                    const std::string& title, std::string* error);

}  // namespace mrqp::run
