// mrqp-run's part of the estimation section (docs/estimation.md): the EstimatorHook built from
// the scene, its log columns, what summary.json adds (the true values from the scene's world, the
// estimates, the convergence time) and the plot of each estimate with its ±2σ band (Fig. 10).
#pragma once

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "estimation/estimation_spec.hpp"
#include "estimation/estimator_hook.hpp"
#include "loop/controller.hpp"
#include "loop/log_ring.hpp"

namespace mrqp::run {

class EstimationRun {
 public:
  /// Builds the hook (none when the scene has no estimation section), registers it with the
  /// controller and its columns in the log (before the log is frozen). `cycles`: the run's length
  /// (the history is reserved once).
  EstimationRun(const estimation::EstimationSpec& spec, loop::Controller& controller, loop::LogRing& log,
                long cycles);

  bool active() const noexcept { return hook_ != nullptr; }
  /// After each cycle, outside the loop's counted region: records the estimates' history.
  void record(double t);
  /// The fields summary.json adds: name and JSON value.
  std::vector<std::pair<std::string, std::string>> summaryFields() const;
  /// Adds summaryFields() to the object of the written summary.json at `path` (its closing brace
  /// replaced); false when the file cannot be read or written or does not end with '}'.
  bool appendSummary(const std::string& path) const;
  /// Lines for the end-of-run text.
  void printSummary() const;
  /// DIR/estimation.png (gnuplot over DIR/log.csv); returns the files written.
  std::vector<std::string> writePlots(const std::string& dir, const std::vector<std::string>& columns,
                                      std::string* error) const;

 private:
  estimation::EstimationSpec spec_;
  std::unique_ptr<estimation::EstimatorHook> hook_;
  std::vector<double> t_;
  std::vector<std::vector<double>> mass_;  // per entity
};

/// The first time after which every later value lies within `tolerance` × |truth| of the truth;
/// −1 when the last value does not.
double convergedAfter(const std::vector<double>& t, const std::vector<double>& v, double truth,
                      double tolerance);

}  // namespace mrqp::run
