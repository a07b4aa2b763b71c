// mrqp-model-cost: calls one generated model function N times on one fixed state, so that an
// instruction count of the whole run (valgrind --tool=callgrind) divided by N — after the count
// of a run with N = 0 is subtracted — is the cost of one call. Also prints the mean wall-clock
// time per call (meaningful on a quiet machine only, and never under valgrind).
//
//   mrqp-model-cost MODEL FUNCTION N
//     MODEL     panda | jvrc1            (control/model/urdf; jvrc1 with a floating base)
//     FUNCTION  fk | jacobians | crba | rnea | nle
//       fk         forwardKinematics(q)
//       jacobians  forwardKinematics(q), then frameJacobian(WorldAligned, origin) of every frame
//       crba       crba(q): the joint-space mass matrix
//       rnea       rnea(q, v, a): inverse dynamics
//       nle        nonLinearEffects(q, v): Coriolis, centrifugal and gravity terms
//     N          number of calls, >= 0
//
// tools/model_cost/callgrind_table.sh runs it under callgrind for every model and function.
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <memory>
#include <random>
#include <string>

#include "jvrc1_model.hpp"
#include "model/model_traits.hpp"
#include "panda_model.hpp"

// Outside the anonymous namespace: clang warns of the traits' unused constants inside it.
MRQP_MODEL_TRAITS(panda_model);
MRQP_MODEL_TRAITS(jvrc1_model);

namespace {

// Keeps every result observable, so that no call can be optimised away.
volatile double g_sink = 0.0;

int usage() {
  std::fprintf(stderr,
               "usage: mrqp-model-cost MODEL FUNCTION N\n"
               "  MODEL panda|jvrc1, FUNCTION fk|jacobians|crba|rnea|nle, N >= 0 calls\n");
  return 2;
}

/// Fixed inputs and outputs of one model; heap storage, Data of the larger models is too big for
/// a comfortable stack.
template <class M>
struct Work {
  typename M::ConfigVector q;
  typename M::TangentVector v, a, out;
  std::unique_ptr<typename M::Data> d = std::make_unique<typename M::Data>();
  std::unique_ptr<typename M::Jacobian> J = std::make_unique<typename M::Jacobian>();
  std::unique_ptr<typename M::MassMatrix> Mm = std::make_unique<typename M::MassMatrix>();
};

enum class Fn { fk, jacobians, crba, rnea, nle };

/// The measured part: n calls, nothing else. Not inlined, so that callgrind can count this
/// function alone (callgrind_table.sh: --toggle-collect='*measuredCalls*').
template <class M>
__attribute__((noinline)) void measuredCalls(Work<M>& w, Fn fn, long n) {
  switch (fn) {
    case Fn::fk:
      for (long i = 0; i < n; ++i) {
        M::fk(*w.d, w.q);
        g_sink = w.d->p[M::nbodies - 1](0);
      }
      break;
    case Fn::jacobians:
      for (long i = 0; i < n; ++i) {
        M::fk(*w.d, w.q);
        double acc = 0.0;
        for (int f = 0; f < M::nframes; ++f) {
          M::jacobian(*w.d, f, Eigen::Vector3d::Zero(), true, *w.J);
          acc += (*w.J)(5, M::nv - 1);
        }
        g_sink = acc;
      }
      break;
    case Fn::crba:
      for (long i = 0; i < n; ++i) {
        M::crba(*w.d, w.q, *w.Mm);
        g_sink = (*w.Mm)(M::nv - 1, M::nv - 1);
      }
      break;
    case Fn::rnea:
      for (long i = 0; i < n; ++i) {
        M::rnea(*w.d, w.q, w.v, w.a, w.out);
        g_sink = w.out(M::nv - 1);
      }
      break;
    case Fn::nle:
      for (long i = 0; i < n; ++i) {
        M::nle(*w.d, w.q, w.v, w.out);
        g_sink = w.out(M::nv - 1);
      }
      break;
  }
}

template <class M>
int run(const char* model, const std::string& name, long n) {
  Fn fn;
  if (name == "fk") {
    fn = Fn::fk;
  } else if (name == "jacobians") {
    fn = Fn::jacobians;
  } else if (name == "crba") {
    fn = Fn::crba;
  } else if (name == "rnea") {
    fn = Fn::rnea;
  } else if (name == "nle") {
    fn = Fn::nle;
  } else {
    std::fprintf(stderr, "mrqp-model-cost: unknown function '%s'\n", name.c_str());
    return usage();
  }
  // A fixed pseudo-random state within the joint limits (the same in every run).
  Work<M> w;
  std::mt19937 rng(12345);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  w.q = mrqp::model::sampleConfiguration<M>(rng);
  for (int i = 0; i < M::nv; ++i) w.v(i) = u(rng);
  for (int i = 0; i < M::nv; ++i) w.a(i) = u(rng);

  using Clock = std::chrono::steady_clock;
  const auto t0 = Clock::now();
  measuredCalls<M>(w, fn, n);
  const double s = std::chrono::duration<double>(Clock::now() - t0).count();
  std::printf("%s %s nv %d frames %d calls %ld mean %.3f us/call\n", model, name.c_str(), M::nv, M::nframes,
              n, n > 0 ? 1e6 * s / static_cast<double>(n) : 0.0);
  return 0;
}

}  // namespace

static int unwrappedMain(int argc, char** argv) {
  if (argc != 4) return usage();
  char* end = nullptr;
  const long n = std::strtol(argv[3], &end, 10);
  if (end == argv[3] || *end != '\0' || n < 0) {
    std::fprintf(stderr, "mrqp-model-cost: N must be an integer >= 0, not '%s'\n", argv[3]);
    return usage();
  }
  const std::string model = argv[1], fn = argv[2];
  if (model == "panda") return run<panda_model_model>("panda", fn, n);
  if (model == "jvrc1") return run<jvrc1_model_model>("jvrc1", fn, n);
  std::fprintf(stderr, "mrqp-model-cost: unknown model '%s'\n", argv[1]);
  return usage();
}

// Any exception becomes one error line and exit status 1 (docs/robustness.md).
int main(int argc, char** argv) {
  try {
    return unwrappedMain(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: %s\n", "mrqp-model-cost", e.what());
  } catch (...) {
    std::fprintf(stderr, "%s: unknown error\n", "mrqp-model-cost");
  }
  return 1;
}
