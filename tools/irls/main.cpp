// mrqp-irls RUNDIR: the batch (IRLS) estimate of the parameters an mrqp-run estimated online,
// from the run's log (RUNDIR/log.csv), next to the online filter's final estimate; writes
// RUNDIR/irls.json (or --json PATH) and prints one line per parameter (docs/estimation.md).
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <fstream>
#include <string>

#include "irls_log.hpp"

namespace {

void usage() {
  std::fprintf(stderr,
               "usage: mrqp-irls RUNDIR [--with-prior] [--huber-k K] [--json PATH]\n"
               "  RUNDIR        an mrqp-run output directory with log.csv (a scene with an estimation section)\n"
               "  --with-prior  add the filter's prior (the log's first θ and σ) as rows\n"
               "  --huber-k K   Huber threshold in units of σ (default 1.345)\n"
               "  --json PATH   where to write the JSON (default RUNDIR/irls.json)\n");
}

}  // namespace

int main(int argc, char** argv) {
  try {
    std::string dir, json;
    bool with_prior = false;
    mrqp::estimation::IrlsOptions options;
    for (int i = 1; i < argc; ++i) {
      const std::string a = argv[i];
      if (a == "--help" || a == "-h") {
        usage();
        return 0;
      } else if (a == "--with-prior") {
        with_prior = true;
      } else if (a == "--huber-k" && i + 1 < argc) {
        char* end = nullptr;
        options.huber_k = std::strtod(argv[++i], &end);
        if (*end != '\0' || !(options.huber_k > 0.0)) throw std::runtime_error("--huber-k: expected a positive number");
      } else if (a == "--json" && i + 1 < argc) {
        json = argv[++i];
      } else if (!a.empty() && a[0] != '-' && dir.empty()) {
        dir = a;
      } else {
        usage();
        throw std::runtime_error("unknown or incomplete option '" + a + "'");
      }
    }
    if (dir.empty()) {
      usage();
      return 2;
    }
    if (json.empty()) json = dir + "/irls.json";
    std::vector<mrqp::irls::BatchResult> results;
    for (const mrqp::irls::EntityBatch& b : mrqp::irls::readBatches(dir + "/log.csv"))
      results.push_back(mrqp::irls::estimate(b, with_prior, options));
    std::fputs(mrqp::irls::toText(results).c_str(), stdout);
    std::ofstream out(json);
    out << mrqp::irls::toJson(results, with_prior, options.huber_k);
    if (!out) throw std::runtime_error(json + ": cannot write");
    std::printf("wrote %s\n", json.c_str());
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "mrqp-irls: %s\n", e.what());
    return 1;
  }
}
