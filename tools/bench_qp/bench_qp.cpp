// bench_qp: timings of the QP solver (docs/qp.md, "Benchmark").
//
//   bench_qp [--data DIR] [--mm] [--random] [--dump FILE|DIR]... [--reps N] [--steps N] [--seed S]
//            [--gradient-scale G]
//
// --mm      the Maros–Meszaros subset of DIR/maros-meszaros (INDEX.tsv order): status, objective
//           error against the reference, iterations and solve times (each problem cold, N reps)
// --random  random dense QPs 60 var / 36 eq / 40 ineq + bounds and 150 / 100 / 150 + bounds:
//           a sequence of `steps` slightly perturbed QPs (a control loop), solved cold and warm;
//           G (default 10) scales g: the larger, the more constraints are active at the optimum
// --dump    QP dump files (docs/qp.md, "The QP text format"), e.g. the controller-scene QPs of
//           DIR/scenes (tests/data/qp/scenes): a directory stands for every *.qp file in it. Each
//           QP is solved N times cold, N times warm and N times warm with the structured path
//           switched off, in turn with one solver, so that all see the same machine: a warm solve
//           starts from the optimal active set of the cold solve just before it (the best case of a
//           control loop whose active set does not change between cycles). "warm path" says which
//           path answered the warm solve: the structured path (previous active set verified
//           optimal, docs/qp.md) or the dense path (factorisation and active set rebuilt)
// Without --mm / --random / --dump, --mm and --random run. Times are per solve() call, single thread: wall clock
// (median, p90, p99, max) and, because a shared machine inflates wall time, the median of the
// thread's CPU time as well. The 1-minute load average is printed for context.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <exception>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "qp/qp_io.hpp"
#include "qp/qp_random.hpp"
#include "qp/qp_solver.hpp"

using mrqp::qp::QpProblem;
using mrqp::qp::QpSolver;
using mrqp::qp::QpStatus;
using mrqp::qp::QpText;

namespace {

using Clock = std::chrono::steady_clock;

struct Stats {
  double median = 0, p90 = 0, p99 = 0, max = 0, mean = 0;
};

Stats stats(std::vector<double> v) {
  Stats s;
  if (v.empty()) return s;
  std::sort(v.begin(), v.end());
  auto at = [&](double f) {
    const auto i = static_cast<std::size_t>(std::ceil(f * static_cast<double>(v.size()))) - 1;
    return v[std::min(v.size() - 1, i)];
  };
  s.median = v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
  s.p90 = at(0.90);
  s.p99 = at(0.99);
  s.max = v.back();
  double sum = 0;
  for (double x : v) sum += x;
  s.mean = sum / static_cast<double>(v.size());
  return s;
}

double cpuMicros() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) * 1e6 + static_cast<double>(t.tv_nsec) * 1e-3;
}

struct Timing {
  std::vector<double> wall, cpu;
};

void solveTimed(QpSolver& solver, const QpProblem& p, Timing& timing) {
  const double c0 = cpuMicros();
  const auto t0 = Clock::now();
  solver.solve(p);
  const auto t1 = Clock::now();
  const double c1 = cpuMicros();
  timing.wall.push_back(std::chrono::duration<double, std::micro>(t1 - t0).count());
  timing.cpu.push_back(c1 - c0);
}

std::string loadAverage() {
  std::ifstream in("/proc/loadavg");
  std::string one;
  in >> one;
  return one.empty() ? std::string("?") : one;
}

int runMarosMeszaros(const std::string& dir, int reps) {
  std::ifstream index(dir + "/INDEX.tsv");
  if (!index) {
    std::fprintf(stderr, "bench_qp: cannot open %s/INDEX.tsv\n", dir.c_str());
    return 1;
  }
  std::string line;
  std::getline(index, line);  // header
  std::printf("## Maros–Meszaros subset (%s), cold start, %d solves each\n\n", dir.c_str(), reps);
  std::printf(
      "| problem | n | m (eq) | P | status | iter | prox | rel. obj. error | primal res. | median µs | max "
      "µs | CPU median µs |\n");
  std::printf("|---|---:|---:|:-:|---|---:|---:|---:|---:|---:|---:|---:|\n");
  int ok_pd = 0, n_pd = 0, ok_psd = 0, honest_psd = 0, n_psd = 0, wrong = 0;
  while (std::getline(index, line)) {
    std::istringstream ss(line);
    std::string name;
    int n = 0, m = 0, meq = 0, posdef = 0;
    ss >> name >> n >> m >> meq >> posdef;
    QpText qp;
    std::string error;
    if (!mrqp::qp::readQpFile(dir + "/" + name + ".qp", qp, error)) {
      std::fprintf(stderr, "bench_qp: %s\n", error.c_str());
      return 1;
    }
    QpProblem problem(qp.n, qp.me, qp.mi);
    mrqp::qp::toProblem(qp, problem);
    QpSolver solver(problem);
    solver.settings().warm_start = false;
    Timing timing;
    for (int k = 0; k < reps; ++k) solveTimed(solver, problem, timing);
    const auto& info = solver.info();
    const double f = mrqp::qp::evaluateObjective(qp, solver.x());
    const double err = std::abs(f - qp.objective) / std::max(1.0, std::abs(qp.objective));
    const bool optimal = info.status == QpStatus::Optimal;
    const bool match = optimal && err <= 1e-6;
    if (posdef) {
      ++n_pd;
      ok_pd += match;
    } else {
      ++n_psd;
      ok_psd += match;
      honest_psd += match || !optimal;
    }
    wrong += optimal && !match;
    const Stats s = stats(timing.wall), c = stats(timing.cpu);
    char errbuf[32];
    if (optimal)
      std::snprintf(errbuf, sizeof errbuf, "%.1e", err);
    else
      std::snprintf(errbuf, sizeof errbuf, "—");
    std::printf("| %s | %d | %d (%d) | %s | %s | %d | %d | %s | %.1e | %.0f | %.0f | %.0f |\n", name.c_str(),
                n, m, meq, posdef ? "PD" : "PSD", mrqp::qp::toString(info.status), info.iterations,
                info.proximal_iterations, errbuf, info.primal_residual, s.median, s.max, c.median);
  }
  std::printf(
      "\nPD problems matching the reference: %d / %d; PSD: %d / %d match, %d / %d match or "
      "report non-optimal; wrong \"optimal\": %d\n\n",
      ok_pd, n_pd, ok_psd, n_psd, honest_psd, n_psd, wrong);
  return 0;
}

void runRandom(const char* label, const mrqp::qp::RandomQpSpec& spec, int steps, unsigned seed) {
  for (int warm = 0; warm < 2; ++warm) {
    // a control loop: each QP is the previous one slightly perturbed, written in place just
    // before the solve (as the controller does); the same seed gives both runs the same sequence
    std::mt19937_64 rng(seed);
    QpProblem p(spec.n, spec.me, spec.mi);
    mrqp::qp::generateRandomQp(spec, rng, p);
    QpSolver solver(p);
    solver.settings().warm_start = warm != 0;
    Timing timing;
    std::vector<double> iters;
    int failures = 0, restarts = 0, active = 0;
    for (int k = 0; k < steps; ++k) {
      mrqp::qp::perturbQp(1e-3, rng, p);
      solveTimed(solver, p, timing);
      iters.push_back(solver.info().iterations);
      failures += solver.status() != QpStatus::Optimal;
      restarts += solver.info().cold_restarted;
      active += solver.info().active_inequalities + solver.info().active_bounds;
    }
    const Stats t = stats(timing.wall), c = stats(timing.cpu), it = stats(iters);
    std::printf("| %s | %s | %.0f | %.0f | %.0f | %.0f | %.0f | %.1f | %.0f | %.1f | %d | %d |\n", label,
                warm ? "warm" : "cold", t.median, t.p90, t.p99, t.max, c.median, it.mean, it.max,
                static_cast<double>(active) / steps, failures, restarts);
  }
}

/// The files named on the command line, a directory expanded to its *.qp files in name order.
bool expandDumps(const std::vector<std::string>& args, std::vector<std::string>& files) {
  namespace fs = std::filesystem;
  for (const auto& a : args) {
    std::error_code ec;
    if (fs::is_directory(a, ec)) {
      std::vector<std::string> in_dir;
      for (const auto& e : fs::directory_iterator(a, ec))
        if (e.is_regular_file() && e.path().extension() == ".qp") in_dir.push_back(e.path().string());
      if (ec || in_dir.empty()) {
        std::fprintf(stderr, "bench_qp: no .qp file in %s\n", a.c_str());
        return false;
      }
      std::sort(in_dir.begin(), in_dir.end());
      files.insert(files.end(), in_dir.begin(), in_dir.end());
    } else {
      files.push_back(a);
    }
  }
  return true;
}

int runDumps(const std::vector<std::string>& files, int reps) {
  std::printf(
      "## QP dumps, each solved %d times cold, %d times warm (from its own optimal active set) and %d "
      "times warm on the dense path only, in turn\n\n",
      reps, reps, reps);
  std::printf(
      "| QP | n | eq | ineq | status | cold steps | cold median µs | cold max µs | cold CPU median µs | "
      "warm path | warm steps | warm median µs | warm max µs | warm CPU median µs | warm dense median µs | "
      "active | primal res. | dual res. |\n");
  std::printf("|---|---:|---:|---:|---|---:|---:|---:|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|\n");
  int failures = 0;
  for (const auto& file : files) {
    QpText qp;
    std::string error;
    if (!mrqp::qp::readQpFile(file, qp, error)) {
      std::fprintf(stderr, "bench_qp: %s: %s\n", file.c_str(), error.c_str());
      return 1;
    }
    QpProblem problem(qp.n, qp.me, qp.mi);
    mrqp::qp::toProblem(qp, problem);
    QpSolver solver(problem);
    Timing tc, tw, td;
    mrqp::qp::QpInfo ci, wi, di;
    for (int k = 0; k < reps; ++k) {
      solver.settings().warm_start = false;
      solveTimed(solver, problem, tc);
      ci = solver.info();
      solver.settings().warm_start = true;  // from the active set the cold solve just found
      solveTimed(solver, problem, tw);
      wi = solver.info();
      solver.settings().structured_path = false;  // the same warm solve on the dense path
      solveTimed(solver, problem, td);
      di = solver.info();
      solver.settings().structured_path = true;
    }
    const bool ok =
        ci.status == QpStatus::Optimal && wi.status == QpStatus::Optimal && di.status == QpStatus::Optimal;
    failures += !ok;
    const Stats c = stats(tc.wall), cc = stats(tc.cpu), w = stats(tw.wall), wc = stats(tw.cpu),
                d = stats(td.wall);
    std::printf(
        "| %s | %d | %d | %d | %s%s%s | %d | %.0f | %.0f | %.0f | %s | %d | %.0f | %.0f | %.0f | %.0f | %d | "
        "%.1e | %.1e |\n",
        qp.name.c_str(), qp.n, qp.me, qp.mi, mrqp::qp::toString(ci.status), ok ? "" : " / ",
        ok ? "" : mrqp::qp::toString(wi.status), ci.iterations, c.median, c.max, cc.median,
        wi.structured ? "structured" : "dense", wi.iterations, w.median, w.max, wc.median, d.median,
        ci.active_inequalities + ci.active_bounds, ci.primal_residual, ci.dual_residual);
  }
  std::printf("\nnot optimal: %d of %zu\n\n", failures, files.size());
  return failures ? 1 : 0;
}

}  // namespace

static int unwrappedMain(int argc, char** argv) {
  std::string dir = MRQP_QP_DATA_DIR;
  bool mm = false, random = false;
  int reps = 20, steps = 1000;
  unsigned seed = 1;
  double gscale = 10.0;
  std::vector<std::string> dump_args;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&]() -> const char* {
      if (i + 1 >= argc) {
        std::fprintf(stderr, "bench_qp: %s needs a value\n", a.c_str());
        std::exit(2);
      }
      return argv[++i];
    };
    if (a == "--data")
      dir = value();
    else if (a == "--mm")
      mm = true;
    else if (a == "--random")
      random = true;
    else if (a == "--dump")
      dump_args.push_back(value());
    else if (a == "--reps")
      reps = std::max(1, std::atoi(value()));
    else if (a == "--steps")
      steps = std::max(1, std::atoi(value()));
    else if (a == "--seed")
      seed = static_cast<unsigned>(std::atoi(value()));
    else if (a == "--gradient-scale")
      gscale = std::atof(value());
    else {
      std::fprintf(stderr,
                   "usage: bench_qp [--data DIR] [--mm] [--random] [--dump FILE|DIR]... [--reps N] "
                   "[--steps N] [--seed S] [--gradient-scale G]\n");
      return 2;
    }
  }
  std::vector<std::string> dumps;
  if (!expandDumps(dump_args, dumps)) return 1;
  if (!mm && !random && dumps.empty()) mm = random = true;
  std::printf("# bench_qp (load average %s)\n\n", loadAverage().c_str());
  if (!dumps.empty() && runDumps(dumps, reps) != 0) return 1;
  if (mm && runMarosMeszaros(dir + "/maros-meszaros", reps) != 0) return 1;
  if (random) {
    std::printf("## Random dense QPs: %d perturbed QPs in sequence (seed %u, gradient scale %g)\n\n", steps,
                seed, gscale);
    std::printf(
        "| problem | start | median µs | p90 µs | p99 µs | max µs | CPU median µs | mean iter | "
        "max iter | active | failures | cold restarts |\n");
    std::printf("|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
    mrqp::qp::RandomQpSpec small;
    small.n = 60;
    small.me = 36;
    small.mi = 40;
    small.gradient_scale = gscale;
    runRandom("60 var / 36 eq / 40 ineq + bounds", small, steps, seed);
    mrqp::qp::RandomQpSpec big;
    big.n = 150;
    big.me = 100;
    big.mi = 150;
    big.gradient_scale = gscale;
    runRandom("150 var / 100 eq / 150 ineq + bounds", big, steps, seed + 1);
    std::printf("\n");
  }
  return 0;
}

// Any exception becomes one error line and exit status 1 (docs/robustness.md).
int main(int argc, char** argv) {
  try {
    return unwrappedMain(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: %s\n", "bench_qp", e.what());
  } catch (...) {
    std::fprintf(stderr, "%s: unknown error\n", "bench_qp");
  }
  return 1;
}
