// mrqp-model-summary: one table row per generated test model — structure (URDF links, merged
// bodies, moving joints, nq, nv, base, mass) and the median wall-clock time of the generated
// forwardKinematics, FK + every frame Jacobian, crba, rnea and regressor.
//
//   mrqp-model-summary [--csv FILE] [--reps N] [--batches N]
//
// Timing: std::chrono::steady_clock around batches of calls on one fixed state; a warm-up of at
// least 20 ms calibrates the batch size (about 1 ms per batch, at most --reps calls, default
// 2000), then the median over --batches batches (default 15) of the mean time per call.
// The table goes to stdout as Markdown, progress to stderr.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <fstream>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "model_set.hpp"

namespace {

using Clock = std::chrono::steady_clock;

struct Options {
  std::string csv;
  int max_reps = 2000;
  int batches = 15;
};

struct Row {
  std::string model;
  int links = 0, bodies = 0, moving = 0, independent = 0, nq = 0, nv = 0;
  bool floating = false;
  double mass = 0.0;
  double fk = 0.0, jac = 0.0, crba = 0.0, rnea = 0.0, regressor = 0.0;  // µs
};

double seconds(Clock::duration d) { return std::chrono::duration<double>(d).count(); }

// Keeps results observable so that no call can be optimised away.
volatile double g_sink = 0.0;

/// Median over `batches` batches of the mean time per call of f, in microseconds.
template <class F>
double medianMicros(F&& f, const Options& opt) {
  constexpr double kWarmup = 0.020;       // s
  constexpr double kBatchTarget = 0.001;  // s
  int n = 0;
  const auto w0 = Clock::now();
  double elapsed = 0.0;
  do {
    f();
    ++n;
    elapsed = seconds(Clock::now() - w0);
  } while (elapsed < kWarmup && n < 100 * opt.max_reps);
  const double per_call = elapsed / n;
  const int reps = std::clamp(static_cast<int>(kBatchTarget / per_call), 1, opt.max_reps);

  std::vector<double> times;
  times.reserve(static_cast<size_t>(opt.batches));
  for (int b = 0; b < opt.batches; ++b) {
    const auto t0 = Clock::now();
    for (int r = 0; r < reps; ++r) f();
    times.push_back(seconds(Clock::now() - t0) / reps * 1e6);
  }
  auto mid = times.begin() + static_cast<std::ptrdiff_t>(times.size() / 2);
  std::nth_element(times.begin(), mid, times.end());
  return *mid;
}

template <class M>
Row measure(const Options& opt) {
  Row row;
  row.model = M::name;
  row.links = M::nframes;
  row.bodies = M::nbodies;
  row.moving = mrqp::tools::movingJoints<M>();
  row.independent = M::njoints;
  row.nq = M::nq;
  row.nv = M::nv;
  row.floating = M::floating_base;
  row.mass = M::totalMass();

  const mrqp::tools::State<M> s;
  // Heap storage: Data and the regressor of the larger models are far too big for the stack.
  auto d = std::make_unique<typename M::Data>();
  auto J = std::make_unique<typename M::Jacobian>();
  auto Mm = std::make_unique<typename M::MassMatrix>();
  auto tau = std::make_unique<typename M::TangentVector>();
  auto Y = std::make_unique<typename M::Regressor>();
  Y->resize(M::nv, M::nparams);  // dynamic column count on the larger models

  row.fk = medianMicros(
      [&] {
        M::fk(*d, s.q);
        g_sink = d->p[M::nbodies - 1](0);
      },
      opt);
  row.jac = medianMicros(
      [&] {
        M::fk(*d, s.q);
        double acc = 0.0;
        for (int f = 0; f < M::nframes; ++f) {
          M::jacobianWorld(*d, f, *J);
          acc += (*J)(5, M::nv - 1);
        }
        g_sink = acc;
      },
      opt);
  row.crba = medianMicros(
      [&] {
        M::crba(*d, s.q, *Mm);
        g_sink = (*Mm)(M::nv - 1, M::nv - 1);
      },
      opt);
  row.rnea = medianMicros(
      [&] {
        M::rnea(*d, s.q, s.v, s.a, *tau);
        g_sink = (*tau)(M::nv - 1);
      },
      opt);
  row.regressor = medianMicros(
      [&] {
        M::regressor(*d, s.q, s.v, s.a, *Y);
        g_sink = (*Y)(0, M::nparams - 1);
      },
      opt);
  return row;
}

const std::vector<std::string>& headers() {
  static const std::vector<std::string> h = {"model",
                                             "URDF links (frames)",
                                             "bodies (merged)",
                                             "moving joints (indep + mimic)",
                                             "nq",
                                             "nv",
                                             "floating base",
                                             "total mass [kg]",
                                             "FK [us]",
                                             "FK + all frame Jacobians [us]",
                                             "CRBA [us]",
                                             "RNEA [us]",
                                             "regressor [us]"};
  return h;
}

std::string fmt(double x, int prec) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", prec, x);
  return buf;
}

/// Three significant digits, at least two decimals below 10 µs.
std::string fmtTime(double us) {
  if (us < 10.0) return fmt(us, 3);
  if (us < 100.0) return fmt(us, 2);
  if (us < 1000.0) return fmt(us, 1);
  return fmt(us, 0);
}

std::vector<std::string> cells(const Row& r, bool csv) {
  const std::string moving = csv ? std::to_string(r.moving)
                                 : std::to_string(r.moving) + " (" + std::to_string(r.independent) + " + " +
                                       std::to_string(r.moving - r.independent) + ")";
  return {r.model,
          std::to_string(r.links),
          std::to_string(r.bodies),
          moving,
          std::to_string(r.nq),
          std::to_string(r.nv),
          r.floating ? "yes" : "no",
          fmt(r.mass, 3),
          fmtTime(r.fk),
          fmtTime(r.jac),
          fmtTime(r.crba),
          fmtTime(r.rnea),
          fmtTime(r.regressor)};
}

void printMarkdown(const std::vector<Row>& rows, std::ostream& os) {
  const auto& h = headers();
  os << '|';
  for (const auto& c : h) os << ' ' << c << " |";
  os << "\n|";
  for (size_t i = 0; i < h.size(); ++i) os << (i == 0 || i == 6 ? "---|" : "--:|");
  os << '\n';
  for (const auto& r : rows) {
    os << '|';
    for (const auto& c : cells(r, false)) os << ' ' << c << " |";
    os << '\n';
  }
}

bool writeCsv(const std::vector<Row>& rows, const std::string& path) {
  std::ofstream out(path);
  if (!out) return false;
  // Plain columns: moving joints split into independent and mimic, times with full precision.
  out << "model,urdf_links,bodies,moving_joints,independent_joints,mimic_joints,nq,nv,"
         "floating_base,total_mass_kg,fk_us,fk_all_jacobians_us,crba_us,rnea_us,regressor_us\n";
  for (const auto& r : rows) {
    out << r.model << ',' << r.links << ',' << r.bodies << ',' << r.moving << ',' << r.independent << ','
        << (r.moving - r.independent) << ',' << r.nq << ',' << r.nv << ',' << (r.floating ? "yes" : "no")
        << ',' << fmt(r.mass, 6) << ',' << fmt(r.fk, 4) << ',' << fmt(r.jac, 4) << ',' << fmt(r.crba, 4)
        << ',' << fmt(r.rnea, 4) << ',' << fmt(r.regressor, 4) << '\n';
  }
  return static_cast<bool>(out);
}

void usage(std::ostream& os) {
  os << "usage: mrqp-model-summary [--csv FILE] [--reps N] [--batches N]\n"
        "  Prints one Markdown table row per generated test model: structure and median\n"
        "  wall-clock time [us] of FK, FK + all frame Jacobians (world-aligned), CRBA, RNEA\n"
        "  and the regressor.\n"
        "  --csv FILE   also write the table as CSV to FILE\n"
        "  --reps N     at most N calls per timed batch (default 2000)\n"
        "  --batches N  timed batches per function, the median is reported (default 15)\n";
}

bool parseInt(const char* s, int& out) {
  char* end = nullptr;
  const long v = std::strtol(s, &end, 10);
  if (end == s || *end != '\0' || v < 1 || v > 10000000) return false;
  out = static_cast<int>(v);
  return true;
}

}  // namespace

static int unwrappedMain(int argc, char** argv) {
  Options opt;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    const bool has_value = i + 1 < argc;
    if (arg == "-h" || arg == "--help") {
      usage(std::cout);
      return 0;
    } else if (arg == "--csv" && has_value) {
      opt.csv = argv[++i];
    } else if (arg == "--reps" && has_value) {
      if (!parseInt(argv[++i], opt.max_reps)) {
        std::cerr << "mrqp-model-summary: --reps needs a positive integer, got '" << argv[i] << "'\n";
        return 2;
      }
    } else if (arg == "--batches" && has_value) {
      if (!parseInt(argv[++i], opt.batches)) {
        std::cerr << "mrqp-model-summary: --batches needs a positive integer, got '" << argv[i] << "'\n";
        return 2;
      }
    } else {
      std::cerr << "mrqp-model-summary: unknown or incomplete argument '" << arg << "'\n";
      usage(std::cerr);
      return 2;
    }
  }

  std::vector<Row> rows;
  int k = 0;
  mrqp::tools::forEachModel([&](auto face) {
    using M = decltype(face);
    ++k;
    const auto t0 = Clock::now();
    std::cerr << "mrqp-model-summary: [" << k << '/' << mrqp::tools::kModelCount << "] " << M::name << " (nv "
              << M::nv << ", " << M::nframes << " frames) ..." << std::flush;
    rows.push_back(measure<M>(opt));
    std::cerr << " done in " << fmt(seconds(Clock::now() - t0), 2) << " s\n";
  });

  printMarkdown(rows, std::cout);
  if (!opt.csv.empty()) {
    if (!writeCsv(rows, opt.csv)) {
      std::cerr << "mrqp-model-summary: cannot write CSV file '" << opt.csv << "'\n";
      return 1;
    }
    std::cerr << "mrqp-model-summary: CSV written to " << opt.csv << '\n';
  }
  return 0;
}

// Any exception becomes one error line and exit status 1 (docs/robustness.md).
int main(int argc, char** argv) {
  try {
    return unwrappedMain(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: %s\n", "mrqp-model-summary", e.what());
  } catch (...) {
    std::fprintf(stderr, "%s: unknown error\n", "mrqp-model-summary");
  }
  return 1;
}
