// mrqp-scene's plot (see scene_plot.hpp).
#include "scene_plot.hpp"

#include <cstdio>

namespace mrqp::scene_run {

bool plotSceneCsv(const std::string& csv, const std::string& png, const std::string& title, int ntasks,
                  int ncontacts) {
  FILE* gp = popen("gnuplot", "w");
  if (!gp) return false;
  std::fprintf(gp,
               "set terminal pngcairo size 1000,700 font ',10' noenhanced\nset output '%s'\n"
               "set datafile separator ','\nset key outside right\nset multiplot layout 2,1 title '%s'\n"
               "set logscale y\nset ylabel 'task error'\nplot ",
               png.c_str(), title.c_str());
  for (int i = 0; i < ntasks; ++i) {
    std::fprintf(
        gp,
        "%s'%s' every ::1 using 1:(column(%d) > 0 ? column(%d) : 1/0) with lines lw 2 title columnhead(%d)",
        i ? ", " : "", csv.c_str(), 5 + i, 5 + i, 5 + i);
  }
  std::fprintf(gp, "\nunset logscale y\nset ylabel 'contact force (N)'\nset xlabel 't (s)'\nplot ");
  for (int i = 0; i < ncontacts; ++i) {
    const int c = 5 + ntasks + 3 * i;
    std::fprintf(gp,
                 "%s'%s' every ::1 using 1:(sqrt(column(%d)**2 + column(%d)**2 + column(%d)**2)) with lines "
                 "title columnhead(%d)",
                 i ? ", " : "", csv.c_str(), c, c + 1, c + 2, c);
  }
  std::fprintf(gp, "\nunset multiplot\n");
  return pclose(gp) == 0;
}

}  // namespace mrqp::scene_run
