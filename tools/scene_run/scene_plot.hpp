// mrqp-scene's plot: the task errors (log scale, top) and the contact force norms (bottom) of its
// CSV log against time, drawn by gnuplot into a PNG.
#pragma once

#include <string>

namespace mrqp::scene_run {

/// The CSV's columns: t, status, iterations, solve_us, then `ntasks` task errors, then three force
/// components per contact. False when gnuplot failed.
bool plotSceneCsv(const std::string& csv, const std::string& png, const std::string& title, int ntasks,
                  int ncontacts);

}  // namespace mrqp::scene_run
