// mrqp-case-study: the two-robots-one-box study of Sec. II-C, multi-robot QP against decoupled QPs.
#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <string>

#include "case_study.hpp"

namespace {

const char* kUsage =
    "usage: mrqp-case-study --csv FILE [--plot FILE.png] [--dt SECONDS]\n"
    "Simulates t in [0, 10] s: the multi-robot QP (eq. 42) and the best decoupled scheme\n"
    "QP1 -> QP3 -> QP2 (eq. 39), compares them with eq. 44 and eq. 41, and checks Newton's third\n"
    "law in the parallel decoupled scheme (eq. 31-33). Exit status 1 if a check fails.\n";

bool plot(const std::string& csv, const std::string& desired, const std::string& png) {
  const std::string cmd = "gnuplot";
  FILE* g = popen(cmd.c_str(), "w");
  if (!g) return false;
  std::fprintf(
      g,
      "set terminal pngcairo size 900,560 font ',11'\n"
      "set output '%s'\n"
      "set datafile separator ','\n"
      "set key top right\n"
      "set grid\n"
      "set xlabel 't [s]'\n"
      "set ylabel 'box acceleration [m/s^2]'\n"
      "set title 'Two robots push a box: one multi-robot QP vs decoupled QPs (Sec. II-C)'\n"
      "t0 = sqrt(6) - 2\n"
      "set arrow from t0, graph 0 to t0, graph 1 nohead dt 2 lc rgb 'gray40'\n"
      "set label 't = sqrt(6) - 2' at t0 + 0.1, 0.9\n"
      "plot '%s' every ::1 using 1:4 with lines lw 2 lc rgb '#1f77b4' title 'multi-robot QP (eq. 43)', \\\n"
      "     '' every ::1 using 1:5 with lines lw 2 lc rgb '#2ca02c' title 'QP1 -> QP3 -> QP2 (eq. 40)', \\\n"
      "     '%s' using 1:2 with lines lw 1 dt 3 lc rgb '#d62728' title 'desired (QP1 -> QP3 -> QP2)', \\\n"
      "     0.5 with lines lw 1 dt 2 lc rgb 'gray40' title 'saturation tau = 1/2'\n",
      png.c_str(), csv.c_str(), desired.c_str());
  return pclose(g) == 0;
}

}  // namespace

static int unwrappedMain(int argc, char** argv) {
  std::string csv, png;
  double dt = 1e-3;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if ((a == "--csv" || a == "--plot" || a == "--dt") && i + 1 >= argc) {
      std::fprintf(stderr, "mrqp-case-study: %s needs a value\n%s", a.c_str(), kUsage);
      return 2;
    }
    if (a == "--csv")
      csv = argv[++i];
    else if (a == "--plot")
      png = argv[++i];
    else if (a == "--dt")
      dt = std::atof(argv[++i]);
    else if (a == "-h" || a == "--help") {
      std::fputs(kUsage, stdout);
      return 0;
    } else {
      std::fprintf(stderr, "mrqp-case-study: unknown argument %s\n%s", a.c_str(), kUsage);
      return 2;
    }
  }
  if (csv.empty() || !(dt > 0.0 && dt <= 0.1)) {
    std::fputs(kUsage, stderr);
    return 2;
  }
  FILE* out = std::fopen(csv.c_str(), "w");
  if (!out) {
    std::fprintf(stderr, "mrqp-case-study: cannot write %s: %s\n", csv.c_str(), std::strerror(errno));
    return 1;
  }
  using namespace mrqp::case_study;
  CaseStudy study;
  BoxState all, seq;
  double errAll = 0, errSeq = 0, errAllAcc = 0, errSeqAcc = 0, newtonAll = 0, newtonParallel = 0;
  bool ok = true;
  std::fprintf(out, "t,q31_mrqp,q31_decoupled,qdd31_mrqp,qdd31_decoupled,tau11,tau21\n");
  // the decoupled scheme's desired acceleration (Fig. 2, red) goes to a side file for the plot only
  const std::string desiredFile = csv + ".desired";
  FILE* desired = png.empty() ? nullptr : std::fopen(desiredFile.c_str(), "w");
  const int steps = static_cast<int>(std::lround(10.0 / dt));
  for (int k = 0; k <= steps; ++k) {
    const double t = k * dt;
    const Decision a = study.multiRobot(all);
    const Decision s = study.sequential(seq);
    ok = ok && a.ok && s.ok;
    errAll = std::max(errAll, std::abs(all.q - analyticMultiRobotPosition(t)));
    errSeq = std::max(errSeq, std::abs(seq.q - analyticSequentialPosition(t)));
    errAllAcc = std::max(errAllAcc, std::abs(a.qdd31 - analyticMultiRobotAcceleration(t)));
    // the sequential acceleration jumps nowhere but has a kink at √6 − 2: compare away from it
    if (std::abs(t - (std::sqrt(6.0) - 2.0)) > 2 * dt)
      errSeqAcc = std::max(errSeqAcc, std::abs(s.qdd31 - analyticSequentialAcceleration(t)));
    newtonAll = std::max(newtonAll, a.newtonViolation());
    newtonParallel = std::max(newtonParallel, study.parallel(all).newtonViolation());
    std::fprintf(out, "%.6f,%.12g,%.12g,%.12g,%.12g,%.12g,%.12g\n", t, all.q, seq.q, a.qdd31, s.qdd31,
                 a.tau11, a.tau21);
    if (desired) std::fprintf(desired, "%.6f,%.12g\n", t, desiredAcceleration(seq));
    if (k == steps) break;
    ok = ok && rk4Step(all, dt, [&](const BoxState& x) { return study.multiRobot(x); });
    ok = ok && rk4Step(seq, dt, [&](const BoxState& x) { return study.sequential(x); });
  }
  std::fclose(out);
  if (desired) std::fclose(desired);
  std::printf("multi-robot QP vs eq. 44:          max |q31 error| = %.3g, max |qdd31 error| = %.3g\n", errAll,
              errAllAcc);
  std::printf("QP1 -> QP3 -> QP2 vs eq. 41:       max |q31 error| = %.3g, max |qdd31 error| = %.3g\n", errSeq,
              errSeqAcc);
  std::printf("Newton's third law, multi-robot QP: max |f13 + f31| = %.3g (one variable, by construction)\n",
              newtonAll);
  std::printf("Newton's third law, parallel QPs:   max |f13 + f31| = %.3g (violated)\n", newtonParallel);
  std::printf("CSV: %s\n", csv.c_str());
  if (!png.empty()) {
    const bool plotted = plot(csv, desiredFile, png);
    std::remove(desiredFile.c_str());
    if (plotted)
      std::printf("plot: %s\n", png.c_str());
    else
      std::fprintf(stderr, "mrqp-case-study: gnuplot failed, no plot written\n");
  }
  const bool pass = ok && errAll < 1e-3 && errSeq < 1e-3 && newtonAll < 1e-12 && newtonParallel > 0.1;
  if (!pass) std::fprintf(stderr, "mrqp-case-study: a check failed (solver status or tolerance 1e-3)\n");
  return pass ? 0 : 1;
}

// Any exception becomes one error line and exit status 1 (docs/robustness.md).
int main(int argc, char** argv) {
  try {
    return unwrappedMain(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: %s\n", "mrqp-case-study", e.what());
  } catch (...) {
    std::fprintf(stderr, "%s: unknown error\n", "mrqp-case-study");
  }
  return 1;
}
