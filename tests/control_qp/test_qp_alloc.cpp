// QpSolver::solve allocates nothing: thousands of solves (cold, warm, regularised, infeasible,
// invalid, with the active size changing) run with the global allocator replaced by a counting
// one (malloc family and every operator new) and Eigen's own allocation check switched on. This
// target compiles the solver sources itself with EIGEN_RUNTIME_NO_MALLOC and assertions enabled,
// so any Eigen heap allocation inside a solve aborts the test.
#include <catch2/catch.hpp>

#include <atomic>
#include <cstdlib>
#include <limits>
#include <memory>
#include <new>
#include <random>
#include <vector>

#include "block_qp.hpp"
#include "counting_allocator.hpp"
#include "qp/qp_random.hpp"
#include "qp/qp_solver.hpp"

namespace {

using mrqp::qp::QpProblem;
using mrqp::qp::QpSolver;
using mrqp::qp::QpStatus;

using mrqp::testing::allocationsIn;

}  // namespace

TEST_CASE("qp: the counting allocator is in effect", "[qp][realtime]") {
  static void* volatile sink;  // keeps the compiler from eliding the pairs below
  CHECK(allocationsIn([] {
          sink = ::operator new(8);
          ::operator delete(sink);
        }) == 1);
  CHECK(allocationsIn([] {
          sink = std::malloc(64);
          std::free(sink);
        }) == 1);
  CHECK(allocationsIn([] { std::vector<int> v(10); }) == 1);
}

TEST_CASE("qp: QP solves allocate nothing", "[qp][realtime]") {
  constexpr int N = 160, ME = 110, MI = 160;
  std::mt19937_64 rng(99);
  // every problem lives in storage of the same capacity, built before counting
  std::vector<std::unique_ptr<QpProblem>> problems;
  auto add = [&](const mrqp::qp::RandomQpSpec& spec) {
    problems.push_back(std::make_unique<QpProblem>(N, ME, MI));
    REQUIRE(mrqp::qp::generateRandomQp(spec, rng, *problems.back()));
  };
  mrqp::qp::RandomQpSpec spec;
  spec.n = 60, spec.me = 36, spec.mi = 40;
  add(spec);
  spec.n = 150, spec.me = 100, spec.mi = 150;
  add(spec);
  spec.n = 20, spec.me = 0, spec.mi = 30, spec.bounds = false;
  add(spec);
  spec.n = 40, spec.me = 10, spec.mi = 20, spec.bounds = true, spec.hessian_rank = 15;  // PSD
  add(spec);
  spec.n = 30, spec.me = 5, spec.mi = 10, spec.hessian_rank = -1;
  add(spec);
  problems.back()->C().row(1) = problems.back()->C().row(0);  // duplicated row
  problems.back()->l()(1) = problems.back()->l()(0);
  problems.back()->u()(1) = problems.back()->u()(0);
  problems.back()->A().row(4) = 2.0 * problems.back()->A().row(0);  // dependent equality
  problems.back()->b()(4) = 2.0 * problems.back()->b()(0);
  add(spec);
  problems.back()->xl()(0) = 10.0;  // infeasible: 10 ≤ x0 ≤ 11 against |x0| ≤ 1 from equalities
  problems.back()->xu()(0) = 11.0;
  problems.back()->A().row(0).setZero();
  problems.back()->A()(0, 0) = 1.0;
  problems.back()->b()(0) = 0.0;
  add(spec);
  problems.back()->H()(2, 2) = std::numeric_limits<double>::quiet_NaN();  // invalid
  spec.n = 1, spec.me = 0, spec.mi = 0;
  add(spec);

  QpSolver solver(N, ME, MI);
  QpSolver cold(N, ME, MI);
  cold.settings().warm_start = false;

  // a control loop on each problem (8 problems: 6 optimal, 1 infeasible, 1 invalid): perturb
  // (outside the count), solve warm and cold (counted)
  constexpr long kRounds = 25;
  long allocations = 0, solves = 0, optimal = 0, infeasible = 0, invalid = 0;
  for (int round = 0; round < kRounds; ++round) {
    for (auto& p : problems) {
      for (int step = 0; step < 10; ++step) {
        mrqp::qp::perturbQp(1e-4, rng, *p);
        QpStatus s1 = QpStatus::NotSolved, s2 = QpStatus::NotSolved;
        allocations += allocationsIn([&] {
          s1 = solver.solve(*p);
          s2 = cold.solve(*p);
        });
        solves += 2;
        optimal += (s1 == QpStatus::Optimal) + (s2 == QpStatus::Optimal);
        infeasible += (s1 == QpStatus::Infeasible) + (s2 == QpStatus::Infeasible);
        invalid += (s1 == QpStatus::InvalidInput) + (s2 == QpStatus::InvalidInput);
      }
    }
  }
  CHECK(allocations == 0);
  CHECK(solves == kRounds * 8 * 10 * 2);
  CHECK(optimal == kRounds * 6 * 10 * 2);
  CHECK(infeasible == kRounds * 10 * 2);
  CHECK(invalid == kRounds * 10 * 2);
  // the warm-start path was exercised and also the fallback from a failed warm start
  CHECK(solver.info().warm_started);
}

TEST_CASE("qp: the structured path allocates nothing", "[qp][realtime]") {
  // block-diagonal QPs of the controller's shape in a control loop: most warm solves answered by
  // the structured path, some (the active set moved, a coupling appeared) by the dense path
  constexpr int N = 100, ME = 30, MI = 30;
  std::mt19937_64 rng(41);
  qptest::BlockQpSpec spec;
  spec.nq = 50;
  spec.nl = 40;
  spec.me = 20;
  spec.mi = 16;
  QpProblem p(N, ME, MI);
  const Eigen::VectorXd x0 = qptest::generateBlockQp(spec, rng, p);
  QpSolver solver(N, ME, MI);
  long allocations = 0, structured = 0, fallbacks = 0, optimal = 0;
  for (int step = 0; step < 400; ++step) {
    if (step == 200) p.H()(0, 1) = p.H()(1, 0) = 1e-3 * std::sqrt(p.H()(0, 0) * p.H()(1, 1));
    qptest::perturbBlockQp(step % 20 == 19 ? 0.3 : 1e-3, x0, rng, p);
    QpStatus s = QpStatus::NotSolved;
    allocations += allocationsIn([&] { s = solver.solve(p); });
    optimal += s == QpStatus::Optimal;
    structured += solver.info().structured;
    fallbacks += solver.info().structured_tried && !solver.info().structured;
  }
  CHECK(allocations == 0);
  CHECK(optimal == 400);
  CHECK(structured > 200);
  CHECK(fallbacks > 0);
}
