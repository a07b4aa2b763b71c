// bench_controller: wall-clock time of the control cycle (MultiRobotProblem::update() + solve())
// of scene files run closed loop on their own models, as mrqp-scene runs them (docs/BENCHMARKS.md,
// "Controller cycle").
//
//   bench_controller [--cycles N] [--scene NAME|FILE]... [--csv FILE] [--dump-qp DIR]
//                    [--dump-cycles K,K,...] [--dump-every K] [--no-timing]
//
//   --cycles N     control cycles per scene (default 5000); the scene's own duration is ignored
//   --scene S      a scene: a file, or a NAME of tools/scenes (NAME.yaml); repeatable. Default:
//                  panda_reach, jvrc1_standing and comanipulation
//   --csv FILE     writes one line per cycle: scene, cycle, update, solve and cycle time (µs), the
//                  thread's CPU time of the cycle (µs), the solver status and its steps
//   --dump-qp DIR  writes the QP of cycles 0 and 1000 of every scene (as assembled by update(),
//                  before the solve) in the QP text format (docs/qp.md) as DIR/<scene>_c<k>.qp
//   --dump-cycles L  the cycles --dump-qp writes, a comma-separated list (default 0,1000); the
//                  assembly records of tests/data/qp/assembly are --dump-cycles 0,1,500
//   --dump-every K --dump-qp writes cycles 0, K, 2K, … (a sequence of a closed loop), and the
//                  cycles of --dump-cycles only if that option is given too
//   --no-timing    runs the cycles and nothing else (no clock is read): for instruction counts,
//                  valgrind --tool=callgrind --toggle-collect='*MultiRobotProblem::update*'
//                  --toggle-collect='*MultiRobotProblem::solve*' (callgrind_cycles.sh)
//
// Each cycle is update() (models, QP assembly), then solve(); the returned q̈ is integrated over
// the scene's dt (the model as its own plant; not timed). A cycle whose solve is not Optimal stops
// the scene and makes the exit status 1. Single thread, nothing pinned: nproc, the CPU model and
// the 1-minute load average are printed for context.
#include <sched.h>
#include <time.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "loop/solution_integrator.hpp"
#include "qp/qp_io.hpp"
#include "scene/builtin_models.hpp"
#include "scene/scene_builder.hpp"

namespace {

using Clock = std::chrono::steady_clock;
using mrqp::qp::QpStatus;

struct Options {
  long cycles = 5000;
  std::vector<std::string> scenes;
  std::string csv, dump_dir;
  std::vector<long> dump_cycles{0, 1000};
  bool dump_cycles_given = false;
  long dump_every = 0;
  bool timing = true;
};

int usage(const char* msg) {
  if (msg) std::fprintf(stderr, "bench_controller: %s\n", msg);
  std::fprintf(stderr,
               "usage: bench_controller [--cycles N] [--scene NAME|FILE]... [--csv FILE] [--dump-qp DIR] "
               "[--dump-cycles K,K,...] [--dump-every K] [--no-timing]\n"
               "  Runs each scene closed loop for N cycles (default 5000) and prints the time of\n"
               "  update() + solve() per cycle. Default scenes: panda_reach jvrc1_standing comanipulation\n"
               "  (%s).\n",
               MRQP_BENCH_SCENES_DIR);
  return msg ? 2 : 0;
}

/// A NAME without '/' and without ".yaml" is a scene of tools/scenes.
std::string resolveScene(const std::string& s) {
  const bool is_path =
      s.find('/') != std::string::npos || (s.size() > 5 && s.compare(s.size() - 5, 5, ".yaml") == 0);
  return is_path ? s : std::string(MRQP_BENCH_SCENES_DIR) + "/" + s + ".yaml";
}

/// The file name without directory and extension.
std::string sceneName(const std::string& path) {
  const auto slash = path.find_last_of('/');
  std::string name = slash == std::string::npos ? path : path.substr(slash + 1);
  const auto dot = name.find_last_of('.');
  return dot == std::string::npos ? name : name.substr(0, dot);
}

int processorCount() {
  cpu_set_t set;
  CPU_ZERO(&set);
  if (sched_getaffinity(0, sizeof set, &set) == 0) return CPU_COUNT(&set);
  return -1;
}

std::string firstLineWith(const char* file, const std::string& key) {
  std::ifstream in(file);
  std::string line;
  while (std::getline(in, line))
    if (line.compare(0, key.size(), key) == 0) return line;
  return "?";
}

std::string loadAverage() {
  std::ifstream in("/proc/loadavg");
  std::string one;
  in >> one;
  return one.empty() ? std::string("?") : one;
}

double cpuMicros() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) * 1e6 + static_cast<double>(t.tv_nsec) * 1e-3;
}

double micros(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double, std::micro>(b - a).count();
}

struct Stats {
  double median = 0, p90 = 0, p99 = 0, max = 0;
};

/// Nearest-rank percentiles (as bench_qp).
Stats stats(std::vector<double> v) {
  Stats s;
  if (v.empty()) return s;
  std::sort(v.begin(), v.end());
  auto at = [&](double f) {
    const auto i = static_cast<std::size_t>(std::ceil(f * static_cast<double>(v.size())));
    return v[std::min(v.size() - 1, i == 0 ? 0 : i - 1)];
  };
  s.median = v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
  s.p90 = at(0.90);
  s.p99 = at(0.99);
  s.max = v.back();
  return s;
}

struct SceneResult {
  std::string name;
  int n_min = 0, n_max = 0, me_min = 0, me_max = 0, mi_min = 0, mi_max = 0;
  long cycles_done = 0;
  bool failed = false;
  Stats cycle, update, solve, cpu;
  double mean_iterations = 0.0;
  int max_iterations = 0;
  long structured = 0;  ///< solves answered by the solver's structured path
};

std::string range(int lo, int hi) {
  return lo == hi ? std::to_string(lo) : std::to_string(lo) + "–" + std::to_string(hi);
}

bool dumpCycle(const Options& opt, long k) {
  if (opt.dump_every > 0 && k % opt.dump_every == 0) return true;
  if (opt.dump_every > 0 && !opt.dump_cycles_given) return false;
  return std::find(opt.dump_cycles.begin(), opt.dump_cycles.end(), k) != opt.dump_cycles.end();
}

/// "0,1,500" → {0, 1, 500}; false on anything but non-negative integers.
bool parseCycles(const std::string& text, std::vector<long>& out) {
  out.clear();
  std::size_t pos = 0;
  while (pos <= text.size()) {
    const std::size_t end = std::min(text.find(',', pos), text.size());
    const std::string item = text.substr(pos, end - pos);
    char* stop = nullptr;
    const long v = std::strtol(item.c_str(), &stop, 10);
    if (item.empty() || *stop != '\0' || v < 0) return false;
    out.push_back(v);
    pos = end + 1;
  }
  return !out.empty();
}

/// Runs one scene closed loop. Returns false on a load error (message printed).
bool runScene(const std::string& path, const Options& opt, std::ofstream& csv, SceneResult& r) {
  mrqp::scene::ModelRegistry models;
  mrqp::scene::addBuiltinModels(models);
  mrqp::scene::Scene scene;
  try {
    scene = mrqp::scene::loadScene(path, models);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_controller: %s\n", e.what());
    return false;
  }
  auto& p = *scene.problem;
  const double dt = scene.settings.dt;
  r.name = sceneName(path);
  const auto n = static_cast<std::size_t>(opt.cycles);
  std::vector<double> t_update, t_solve, t_cycle, t_cpu;
  if (opt.timing) {
    t_update.reserve(n);
    t_solve.reserve(n);
    t_cycle.reserve(n);
    t_cpu.reserve(n);
  }
  long iterations = 0;
  r.n_min = r.me_min = r.mi_min = 1 << 30;
  for (long k = 0; k < opt.cycles; ++k) {
    QpStatus st;
    if (opt.timing) {
      const double c0 = cpuMicros();
      const auto t0 = Clock::now();
      p.update();
      const auto t1 = Clock::now();
      const double c1 = cpuMicros();
      // The dump is written between the two timed parts and timed by neither.
      if (!opt.dump_dir.empty() && dumpCycle(opt, k)) {
        const std::string name = r.name + "_c" + std::to_string(k);
        std::string error;
        if (!mrqp::qp::dumpProblem(opt.dump_dir + "/" + name + ".qp", p.qp(), name, error)) {
          std::fprintf(stderr, "bench_controller: %s\n", error.c_str());
          return false;
        }
      }
      const double c2 = cpuMicros();
      const auto t2 = Clock::now();
      st = p.solve();
      const auto t3 = Clock::now();
      const double c3 = cpuMicros();
      t_update.push_back(micros(t0, t1));
      t_solve.push_back(micros(t2, t3));
      t_cycle.push_back(t_update.back() + t_solve.back());
      t_cpu.push_back((c1 - c0) + (c3 - c2));
      if (csv)
        csv << r.name << ',' << k << ',' << t_update.back() << ',' << t_solve.back() << ',' << t_cycle.back()
            << ',' << t_cpu.back() << ',' << mrqp::qp::toString(st) << ',' << p.solver().info().iterations
            << '\n';
    } else {
      p.update();
      st = p.solve();
    }
    const auto& qp = p.qp();
    r.n_min = std::min(r.n_min, qp.n());
    r.n_max = std::max(r.n_max, qp.n());
    r.me_min = std::min(r.me_min, qp.me());
    r.me_max = std::max(r.me_max, qp.me());
    r.mi_min = std::min(r.mi_min, qp.mi());
    r.mi_max = std::max(r.mi_max, qp.mi());
    iterations += p.solver().info().iterations;
    r.structured += p.solver().info().structured ? 1 : 0;
    r.max_iterations = std::max(r.max_iterations, p.solver().info().iterations);
    r.cycles_done = k + 1;
    if (st != QpStatus::Optimal) {
      std::fprintf(stderr, "bench_controller: %s: cycle %ld (t = %.3f s): the QP is %s: scene stopped\n",
                   r.name.c_str(), k, static_cast<double>(k) * dt, mrqp::qp::toString(st));
      r.failed = true;
      break;
    }
    mrqp::loop::integrateSolution(p, dt);
  }
  r.mean_iterations = static_cast<double>(iterations) / static_cast<double>(std::max(1L, r.cycles_done));
  if (opt.timing) {
    r.cycle = stats(t_cycle);
    r.update = stats(t_update);
    r.solve = stats(t_solve);
    r.cpu = stats(t_cpu);
  }
  return true;
}

}  // namespace

static int unwrappedMain(int argc, char** argv) {
  Options opt;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto next = [&]() -> const char* { return i + 1 < argc ? argv[++i] : nullptr; };
    if (a == "--cycles") {
      const char* v = next();
      if (!v || std::atol(v) < 1) return usage("--cycles needs a positive integer");
      opt.cycles = std::atol(v);
    } else if (a == "--scene") {
      const char* v = next();
      if (!v) return usage("--scene needs a name or a file");
      opt.scenes.push_back(resolveScene(v));
    } else if (a == "--csv") {
      const char* v = next();
      if (!v) return usage("--csv needs a file");
      opt.csv = v;
    } else if (a == "--dump-qp") {
      const char* v = next();
      if (!v) return usage("--dump-qp needs a directory");
      opt.dump_dir = v;
    } else if (a == "--dump-cycles") {
      const char* v = next();
      if (!v || !parseCycles(v, opt.dump_cycles)) return usage("--dump-cycles needs a list like 0,1,500");
      opt.dump_cycles_given = true;
    } else if (a == "--dump-every") {
      const char* v = next();
      char* stop = nullptr;
      const long k = v ? std::strtol(v, &stop, 10) : 0;
      if (!v || *stop != '\0' || k < 1) return usage("--dump-every needs a positive integer");
      opt.dump_every = k;
    } else if (a == "--no-timing") {
      opt.timing = false;
    } else if (a == "-h" || a == "--help") {
      return usage(nullptr);
    } else {
      return usage(("unknown option " + a).c_str());
    }
  }
  if (opt.scenes.empty())
    for (const char* s : {"panda_reach", "jvrc1_standing", "comanipulation"})
      opt.scenes.push_back(resolveScene(s));
  if (!opt.timing && (!opt.csv.empty() || !opt.dump_dir.empty()))
    return usage("--csv and --dump-qp need the timed run (no --no-timing)");

  std::ofstream csv;
  if (!opt.csv.empty()) {
    csv.open(opt.csv);
    if (!csv) {
      std::fprintf(stderr, "bench_controller: cannot write %s\n", opt.csv.c_str());
      return 1;
    }
    csv << "scene,cycle,update_us,solve_us,cycle_us,cpu_us,status,iterations\n";
  }

  if (opt.timing) {
    std::printf("# bench_controller: %ld cycles per scene, update() + solve(), wall clock\n\n", opt.cycles);
    std::printf("nproc: %d\n%s\nload average (1 min) at start: %s\n\n", processorCount(),
                firstLineWith("/proc/cpuinfo", "model name").c_str(), loadAverage().c_str());
  }
  std::vector<SceneResult> results;
  bool ok = true;
  for (const auto& path : opt.scenes) {
    SceneResult r;
    if (!runScene(path, opt, csv, r)) return 1;
    ok = ok && !r.failed;
    if (!opt.timing)
      std::printf("%s: %ld cycles, n %s, me %s, mi %s, mean solver steps %.2f, structured path %ld%s\n",
                  r.name.c_str(), r.cycles_done, range(r.n_min, r.n_max).c_str(),
                  range(r.me_min, r.me_max).c_str(), range(r.mi_min, r.mi_max).c_str(), r.mean_iterations,
                  r.structured, r.failed ? " (FAILED)" : "");
    results.push_back(r);
  }
  if (opt.timing) {
    std::printf(
        "| scene | n | equalities | inequalities | cycles | median µs | p90 µs | p99 µs | max µs | "
        "update median µs | solve median µs | CPU median µs | CPU p99 µs | mean steps | max steps | "
        "structured |\n");
    std::printf("|---|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|\n");
    for (const auto& r : results)
      std::printf(
          "| %s | %s | %s | %s | %ld%s | %.0f | %.0f | %.0f | %.0f | %.0f | %.0f | %.0f | %.0f | %.2f | %d "
          "| %ld |\n",
          r.name.c_str(), range(r.n_min, r.n_max).c_str(), range(r.me_min, r.me_max).c_str(),
          range(r.mi_min, r.mi_max).c_str(), r.cycles_done, r.failed ? " (failed)" : "", r.cycle.median,
          r.cycle.p90, r.cycle.p99, r.cycle.max, r.update.median, r.solve.median, r.cpu.median, r.cpu.p99,
          r.mean_iterations, r.max_iterations, r.structured);
    std::printf("\nload average (1 min) at end: %s\n", loadAverage().c_str());
    for (const long k : opt.dump_cycles)
      if (!opt.dump_dir.empty() && (opt.dump_every == 0 || opt.dump_cycles_given) && opt.cycles <= k)
        std::printf("note: %ld cycles: cycle %ld was not dumped\n", opt.cycles, k);
  }
  return ok ? 0 : 1;
}

// Any exception becomes one error line and exit status 1 (docs/robustness.md).
int main(int argc, char** argv) {
  try {
    return unwrappedMain(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: %s\n", "bench_controller", e.what());
  } catch (...) {
    std::fprintf(stderr, "%s: unknown error\n", "bench_controller");
  }
  return 1;
}
