// bench_model: generated model code (mrqp-gen) against the slow dynamic-size reference
// implementation (tests/support), on the six models of control/model/urdf and tests/data/models.
//
// Benchmarks, named <model>/<function>/<side> with side "generated" or "reference":
//   fk_all_jacobians  generated: forwardKinematics + frameJacobian(WorldAligned, origin) of every
//                     frame; reference: frameJacobian(q, frame, 0, world_aligned) of every frame
//                     (the reference recomputes its kinematics in each call, as designed)
//   crba              generated: crba;       reference: massMatrix (column-by-column RNEA)
//   rnea              generated: rnea;       reference: rnea
//   regressor         generated: regressor;  reference: none (it cannot change its inertial
//                     parameters, so it has no regressor to time)
// Every benchmark uses one fixed pseudo-random state within the joint limits (seed 12345).
// Before timing, the generated results are checked against the reference at that state; a
// mismatch aborts with exit status 1 so that a table never compares different computations.
//
// Standard Google Benchmark flags apply, e.g.
//   bench_model --benchmark_repetitions=7 --benchmark_report_aggregates_only=true
//               --benchmark_format=json --benchmark_filter='panda/'
#include <benchmark/benchmark.h>

#include <Eigen/Core>

#include <cmath>
#include <cstdio>
#include <exception>
#include <iostream>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "model_set.hpp"
#include "reference_model.hpp"

namespace {

using Eigen::MatrixXd;
using Eigen::VectorXd;
using mrqp::test::ReferenceModel;

double maxAbs(const MatrixXd& m) { return m.size() ? m.cwiseAbs().maxCoeff() : 0.0; }

/// Relative agreement of a with b (scaled by max(1, |b|_max)).
bool close(const MatrixXd& a, const MatrixXd& b, double tol, const std::string& what, const char* model) {
  const double err = maxAbs(a - b) / std::max(1.0, maxAbs(b));
  if (a.rows() == b.rows() && a.cols() == b.cols() && err <= tol) return true;
  std::cerr << "bench_model: " << model << ": " << what << " differs from the reference (relative " << err
            << " > " << tol << ")\n";
  return false;
}

/// Generated vs reference at the benchmark state; also checks that nbodies - 1 (the moving-joint
/// count reported by mrqp-model-summary) equals the URDF's moving joints.
template <class M>
bool check(const ReferenceModel& ref, const mrqp::tools::State<M>& s) {
  bool ok = true;
  const VectorXd q = s.q, v = s.v, a = s.a;
  auto d = std::make_unique<typename M::Data>();
  if (ref.nq() != M::nq || ref.nv() != M::nv || ref.frameNames().size() != size_t{M::nframes}) {
    std::cerr << "bench_model: " << M::name << ": sizes differ from the reference\n";
    return false;
  }
  if (ref.fullJointNames().size() != size_t{mrqp::tools::movingJoints<M>()}) {
    std::cerr << "bench_model: " << M::name << ": " << ref.fullJointNames().size()
              << " moving URDF joints, but nbodies - 1 = " << mrqp::tools::movingJoints<M>() << '\n';
    ok = false;
  }

  auto J = std::make_unique<typename M::Jacobian>();
  M::fk(*d, s.q);
  for (int f = 0; f < M::nframes; ++f) {
    M::jacobianWorld(*d, f, *J);
    const MatrixXd Jg = *J;
    const std::string& name = ref.frameNames()[size_t(f)];
    ok &= close(Jg, ref.frameJacobian(q, name, Eigen::Vector3d::Zero(), true), 1e-9,
                "Jacobian of frame '" + name + "'", M::name);
  }

  auto Mm = std::make_unique<typename M::MassMatrix>();
  M::crba(*d, s.q, *Mm);
  ok &= close(MatrixXd(*Mm), ref.massMatrix(q), 1e-9, "mass matrix", M::name);

  auto tau = std::make_unique<typename M::TangentVector>();
  M::rnea(*d, s.q, s.v, s.a, *tau);
  const VectorXd tau_ref = ref.rnea(q, v, a);
  ok &= close(VectorXd(*tau), tau_ref, 1e-9, "rnea", M::name);

  auto Y = std::make_unique<typename M::Regressor>();
  Y->resize(M::nv, M::nparams);  // dynamic column count on the larger models
  auto phi = std::make_unique<typename M::ParamVector>();
  M::regressor(*d, s.q, s.v, s.a, *Y);
  M::params(*phi);
  ok &= close(VectorXd((*Y) * (*phi)), tau_ref, 1e-9, "regressor * parameters", M::name);
  return ok;
}

/// Registers one benchmark, reported in microseconds.
template <class F>
void add(const std::string& name, F&& f) {
  benchmark::RegisterBenchmark(name.c_str(), std::forward<F>(f))->Unit(benchmark::kMicrosecond);
}

template <class M>
bool registerModel() {
  auto ref = std::make_shared<const ReferenceModel>(ReferenceModel::fromUrdf(M::urdf, M::floating_base));
  auto s = std::make_shared<const mrqp::tools::State<M>>();
  if (!check<M>(*ref, *s)) return false;
  const std::string prefix = std::string(M::name) + "/";

  // ---- generated: fixed-size work space allocated once, outside the timed loop --------------
  add(prefix + "fk_all_jacobians/generated", [s](benchmark::State& st) {
    auto d = std::make_unique<typename M::Data>();
    auto J = std::make_unique<typename M::Jacobian>();
    for (auto _ : st) {
      M::fk(*d, s->q);
      for (int f = 0; f < M::nframes; ++f) {
        M::jacobianWorld(*d, f, *J);
        benchmark::DoNotOptimize(J->data());
        benchmark::ClobberMemory();
      }
    }
  });
  add(prefix + "crba/generated", [s](benchmark::State& st) {
    auto d = std::make_unique<typename M::Data>();
    auto Mm = std::make_unique<typename M::MassMatrix>();
    for (auto _ : st) {
      M::crba(*d, s->q, *Mm);
      benchmark::DoNotOptimize(Mm->data());
      benchmark::ClobberMemory();
    }
  });
  add(prefix + "rnea/generated", [s](benchmark::State& st) {
    auto d = std::make_unique<typename M::Data>();
    auto tau = std::make_unique<typename M::TangentVector>();
    for (auto _ : st) {
      M::rnea(*d, s->q, s->v, s->a, *tau);
      benchmark::DoNotOptimize(tau->data());
      benchmark::ClobberMemory();
    }
  });
  add(prefix + "regressor/generated", [s](benchmark::State& st) {
    auto d = std::make_unique<typename M::Data>();
    auto Y = std::make_unique<typename M::Regressor>();
    Y->resize(M::nv, M::nparams);
    for (auto _ : st) {
      M::regressor(*d, s->q, s->v, s->a, *Y);
      benchmark::DoNotOptimize(Y->data());
      benchmark::ClobberMemory();
    }
  });

  // ---- reference: its public API as it is (dynamic sizes, allocates, frames by name) ---------
  const VectorXd q = s->q, v = s->v, a = s->a;
  add(prefix + "fk_all_jacobians/reference", [ref, q](benchmark::State& st) {
    const auto& frames = ref->frameNames();
    for (auto _ : st) {
      for (const auto& f : frames) {
        MatrixXd J = ref->frameJacobian(q, f, Eigen::Vector3d::Zero(), true);
        benchmark::DoNotOptimize(J.data());
      }
    }
  });
  add(prefix + "crba/reference", [ref, q](benchmark::State& st) {
    for (auto _ : st) {
      MatrixXd Mm = ref->massMatrix(q);
      benchmark::DoNotOptimize(Mm.data());
    }
  });
  add(prefix + "rnea/reference", [ref, q, v, a](benchmark::State& st) {
    for (auto _ : st) {
      VectorXd tau = ref->rnea(q, v, a);
      benchmark::DoNotOptimize(tau.data());
    }
  });
  return true;
}

}  // namespace

static int unwrappedMain(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 2;

  benchmark::AddCustomContext("mrqp_compiler", __VERSION__);
  benchmark::AddCustomContext("mrqp_build_type", MRQP_TOOLS_BUILD_TYPE);
#ifdef NDEBUG
  benchmark::AddCustomContext("mrqp_ndebug", "yes");
#else
  benchmark::AddCustomContext("mrqp_ndebug", "no (assertions on: timings are not representative)");
#endif

  bool ok = true;
  try {
    mrqp::tools::forEachModel([&](auto face) { ok &= registerModel<decltype(face)>(); });
  } catch (const std::exception& e) {
    std::cerr << "bench_model: cannot load a reference model: " << e.what() << '\n';
    return 1;
  }
  if (!ok) return 1;

  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}

// Any exception becomes one error line and exit status 1 (docs/robustness.md).
int main(int argc, char** argv) {
  try {
    return unwrappedMain(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: %s\n", "bench_model", e.what());
  } catch (...) {
    std::fprintf(stderr, "%s: unknown error\n", "bench_model");
  }
  return 1;
}
