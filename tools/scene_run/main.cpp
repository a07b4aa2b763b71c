// mrqp-scene: runs a scene file on its own models through the loop without hardware
// (loop::ModelLoop: the QP's q̈ integrated as the plant) and writes a CSV log of every task error,
// contact force and solver figure per cycle, and a plot of it (scene_plot.hpp).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <exception>
#include <fstream>
#include <string>

#include "loop/model_loop.hpp"
#include "scene/builtin_models.hpp"
#include "scene/scene_builder.hpp"
#include "scene_plot.hpp"

namespace {

int usage(const char* msg) {
  if (msg) std::fprintf(stderr, "mrqp-scene: %s\n", msg);
  std::fprintf(stderr,
               "usage: mrqp-scene --scene FILE.yaml [--csv OUT.csv [--plot OUT.png]] [--duration S]\n"
               "                  [--every N]\n"
               "  Runs the scene for its settings.duration (or S) seconds and logs every N-th cycle;\n"
               "  --plot draws the task errors and contact forces against time (gnuplot).\n");
  return 2;
}

}  // namespace

static int unwrappedMain(int argc, char** argv) {
  std::string scene_file, csv_file, png_file;
  double duration = -1.0;
  int every = 10;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto next = [&]() -> const char* { return i + 1 < argc ? argv[++i] : nullptr; };
    if (a == "--scene") {
      const char* v = next();
      if (!v) return usage("--scene needs a file");
      scene_file = v;
    } else if (a == "--csv") {
      const char* v = next();
      if (!v) return usage("--csv needs a file");
      csv_file = v;
    } else if (a == "--plot") {
      const char* v = next();
      if (!v) return usage("--plot needs a file");
      png_file = v;
    } else if (a == "--duration") {
      const char* v = next();
      if (!v) return usage("--duration needs seconds");
      duration = std::atof(v);
    } else if (a == "--every") {
      const char* v = next();
      if (!v || std::atoi(v) < 1) return usage("--every needs a positive integer");
      every = std::atoi(v);
    } else if (a == "-h" || a == "--help") {
      return usage(nullptr);
    } else {
      return usage(("unknown option " + a).c_str());
    }
  }
  if (scene_file.empty()) return usage("--scene is required");
  if (!png_file.empty() && csv_file.empty()) return usage("--plot needs --csv");

  mrqp::scene::ModelRegistry models;
  mrqp::scene::addBuiltinModels(models);
  mrqp::scene::Scene scene;
  try {
    scene = mrqp::scene::loadScene(scene_file, models);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "mrqp-scene: %s\n", e.what());
    return 1;
  }
  auto& p = *scene.problem;
  const double dt = scene.settings.dt;
  if (duration <= 0.0) duration = scene.settings.duration;
  const long cycles = std::lround(duration / dt);

  std::ofstream csv;
  if (!csv_file.empty()) {
    csv.open(csv_file);
    if (!csv) {
      std::fprintf(stderr, "mrqp-scene: cannot write %s\n", csv_file.c_str());
      return 1;
    }
    csv << "t,status,iterations,solve_us";
    for (const auto& [name, id] : scene.tasks) csv << ",err_" << name;
    for (const auto& [name, id] : scene.contacts) csv << ",fx_" << name << ",fy_" << name << ",fz_" << name;
    csv << "\n";
  }
  std::printf("mrqp-scene: %s: %d entities, %zu contacts, %zu tasks, %ld cycles of %g ms\n",
              scene_file.c_str(), p.entityCount(), scene.contacts.size(), scene.tasks.size(), cycles,
              dt * 1e3);
  mrqp::loop::ModelLoop loop(p);
  double worst_us = 0.0;
  for (long k = 0; k < cycles; ++k) {
    const double t = loop.time();
    const auto st = loop.cycle();
    const auto& timing = loop.lastTiming();
    const double us = static_cast<double>(timing.update_ns + timing.solve_ns) * 1e-3;
    worst_us = std::max(worst_us, us);
    if (st != mrqp::qp::QpStatus::Optimal) {
      std::fprintf(stderr, "mrqp-scene: t = %.3f s: the QP failed (status %d): stopping\n", t,
                   static_cast<int>(st));
      return 1;
    }
    if (csv && k % every == 0) {
      csv << t << "," << static_cast<int>(st) << "," << p.solver().info().iterations << "," << us;
      for (const auto& [name, id] : scene.tasks) csv << "," << p.taskError(id).norm();
      for (const auto& [name, id] : scene.contacts) {
        const Eigen::Vector3d f = p.contactForce(id);
        csv << "," << f.x() << "," << f.y() << "," << f.z();
      }
      csv << "\n";
    }
    if (k % 1000 == 0) std::printf("  t = %5.2f s\n", t);
  }
  std::printf("mrqp-scene: done; final task errors:\n");
  for (const auto& [name, id] : scene.tasks)
    std::printf("  %-16s %.3g\n", name.c_str(), p.taskError(id).norm());
  std::printf("  slowest cycle %.0f µs (wall clock, this machine)\n", worst_us);
  if (!png_file.empty()) {
    csv.close();
    const int ntasks = static_cast<int>(scene.tasks.size());
    const int ncontacts = static_cast<int>(scene.contacts.size());
    if (!mrqp::scene_run::plotSceneCsv(csv_file, png_file, scene_file, ntasks, ncontacts)) {
      std::fprintf(stderr, "mrqp-scene: gnuplot failed: no plot written (the CSV is complete)\n");
      return 1;
    }
    std::printf("mrqp-scene: plot written to %s\n", png_file.c_str());
  }
  return 0;
}

// Any exception becomes one error line and exit status 1 (docs/robustness.md).
int main(int argc, char** argv) {
  try {
    return unwrappedMain(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: %s\n", "mrqp-scene", e.what());
  } catch (...) {
    std::fprintf(stderr, "%s: unknown error\n", "mrqp-scene");
  }
  return 1;
}
