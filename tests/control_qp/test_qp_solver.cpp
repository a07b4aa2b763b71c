// The QP solver checked against independent references: the KKT conditions evaluated from the
// data, brute-force enumeration of every active set, and the closed-form KKT solve of
// equality-only problems; plus degenerate, infeasible and invalid problems, warm start and
// capacity handling.
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <random>

#include "qp/qp_random.hpp"
#include "qp/qp_solver.hpp"
#include "qp_test_util.hpp"

using mrqp::qp::QpInputError;
using mrqp::qp::QpProblem;
using mrqp::qp::QpSolver;
using mrqp::qp::QpStatus;
using mrqp::qp::RandomQpSpec;

namespace {

constexpr double inf = std::numeric_limits<double>::infinity();

Eigen::VectorXd vec(std::initializer_list<double> v) {
  Eigen::VectorXd out(static_cast<Eigen::Index>(v.size()));
  Eigen::Index i = 0;
  for (double x : v) out(i++) = x;
  return out;
}

// A problem with exactly this size and cleared data.
QpProblem makeProblem(int n, int me, int mi) {
  QpProblem p(n, me, mi);
  p.clear();
  return p;
}

}  // namespace

TEST_CASE("qp: random strictly convex QPs satisfy the KKT conditions to 1e-8", "[qp]") {
  struct Size {
    int n, me, mi;
    bool bounds;
  };
  const Size sizes[] = {{1, 0, 0, true},    {2, 1, 1, true},     {5, 0, 5, false},     {5, 2, 3, true},
                        {10, 3, 8, true},   {20, 0, 30, false},  {30, 10, 20, true},   {40, 0, 0, true},
                        {60, 36, 40, true}, {100, 20, 80, true}, {150, 100, 150, true}};
  std::mt19937_64 rng(42);
  int solved = 0;
  for (const Size& s : sizes) {
    for (double gscale : {0.1, 10.0}) {
      for (int seed = 0; seed < 6; ++seed) {
        RandomQpSpec spec;
        spec.n = s.n;
        spec.me = s.me;
        spec.mi = s.mi;
        spec.bounds = s.bounds;
        spec.gradient_scale = gscale;
        QpProblem p(s.n, s.me, s.mi);
        REQUIRE(mrqp::qp::generateRandomQp(spec, rng, p));
        QpSolver solver(p);
        INFO("n " << s.n << " me " << s.me << " mi " << s.mi << " gscale " << gscale << " seed " << seed);
        REQUIRE(solver.solve(p) == QpStatus::Optimal);
        const auto k = qptest::kktErrors(p, solver);
        CHECK(k.stationarity <= 1e-8);
        CHECK(k.primal <= 1e-8);
        CHECK(k.dual <= 1e-8);
        CHECK(k.complementarity <= 1e-8);
        CHECK(solver.objective() == Approx(p.objective(solver.x())).epsilon(1e-12).margin(1e-12));
        CHECK(!solver.info().regularized);
        ++solved;
      }
    }
  }
  CHECK(solved == 132);
}

TEST_CASE("qp: tiny QPs match brute-force enumeration of all active sets", "[qp]") {
  std::mt19937_64 rng(7);
  std::normal_distribution<double> N(0.0, 1.0);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  int optimal = 0, infeasible = 0;
  for (int trial = 0; trial < 400; ++trial) {
    const int n = 1 + trial % 4;
    const int me = static_cast<int>(U(rng) * std::min(2, n));  // 0 .. min(2, n) - 1
    const int mi = static_cast<int>(U(rng) * 4.0);             // 0 .. 3
    QpProblem p = makeProblem(n, me, mi);
    Eigen::MatrixXd M(n, n);
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) M(i, j) = N(rng);
    p.H() = M.transpose() * M + 0.1 * Eigen::MatrixXd::Identity(n, n);
    for (int j = 0; j < n; ++j) p.g()(j) = 3.0 * N(rng);
    for (int i = 0; i < me; ++i) {
      for (int j = 0; j < n; ++j) p.A()(i, j) = N(rng);
      p.b()(i) = N(rng);
    }
    for (int i = 0; i < mi; ++i) {
      for (int j = 0; j < n; ++j) p.C()(i, j) = N(rng);
      const double a = N(rng), w = U(rng) * 2.0;
      p.l()(i) = U(rng) < 0.2 ? -inf : a - w;
      p.u()(i) = U(rng) < 0.2 ? inf : a + w;
    }
    for (int j = 0; j < n; ++j) {
      const double a = 0.5 * N(rng), w = 0.2 + U(rng);
      p.xl()(j) = U(rng) < 0.3 ? -inf : a - w;
      p.xu()(j) = U(rng) < 0.3 ? inf : a + w;
    }
    Eigen::VectorXd xb;
    double fb = 0.0;
    const bool feasible = qptest::bruteForce(p, xb, fb);
    QpSolver solver(p);
    const QpStatus st = solver.solve(p);
    INFO("trial " << trial << " n " << n << " me " << me << " mi " << mi);
    if (feasible) {
      REQUIRE(st == QpStatus::Optimal);
      CHECK(solver.objective() == Approx(fb).epsilon(1e-9).margin(1e-9));
      CHECK((solver.x() - xb).lpNorm<Eigen::Infinity>() <=
            1e-7 * std::max(1.0, xb.lpNorm<Eigen::Infinity>()));
      CHECK(qptest::kktErrors(p, solver).worst() <= 1e-8);
      ++optimal;
    } else {
      CHECK(st == QpStatus::Infeasible);
      ++infeasible;
    }
  }
  // both outcomes must be exercised
  CHECK(optimal > 200);
  CHECK(infeasible > 20);
}

TEST_CASE("qp: equality-only QPs match the closed-form KKT solution", "[qp]") {
  std::mt19937_64 rng(3);
  std::normal_distribution<double> N(0.0, 1.0);
  for (int trial = 0; trial < 30; ++trial) {
    const int n = 2 + trial % 40;
    const int me = 1 + static_cast<int>(trial % n);
    const bool singular_h = trial % 3 == 0;  // H PSD but ZᵀHZ PD: rank(H) = n - me
    QpProblem p = makeProblem(n, me, 0);
    Eigen::MatrixXd M(singular_h ? n - me : n, n);
    for (int i = 0; i < M.rows(); ++i)
      for (int j = 0; j < n; ++j) M(i, j) = N(rng);
    p.H() = M.transpose() * M;
    if (!singular_h) p.H().diagonal().array() += 0.1;
    for (int j = 0; j < n; ++j) p.g()(j) = N(rng);
    for (int i = 0; i < me; ++i) {
      for (int j = 0; j < n; ++j) p.A()(i, j) = N(rng);
      p.b()(i) = N(rng);
    }
    // [H Aᵀ; A 0] [x; y] = [-g; b]   (Hx + g + Aᵀy = 0)
    Eigen::MatrixXd K = Eigen::MatrixXd::Zero(n + me, n + me);
    K.topLeftCorner(n, n) = p.H();
    K.topRightCorner(n, me) = p.A().transpose();
    K.bottomLeftCorner(me, n) = p.A();
    Eigen::VectorXd rhs(n + me);
    rhs << -p.g(), p.b();
    const Eigen::VectorXd sol = K.fullPivLu().solve(rhs);
    QpSolver solver(p);
    INFO("trial " << trial << " n " << n << " me " << me << " singular H " << singular_h);
    REQUIRE(solver.solve(p) == QpStatus::Optimal);
    const double xs = std::max(1.0, sol.head(n).lpNorm<Eigen::Infinity>());
    const double ys = std::max(1.0, sol.tail(me).lpNorm<Eigen::Infinity>());
    CHECK((solver.x() - sol.head(n)).lpNorm<Eigen::Infinity>() <= 1e-9 * xs);
    CHECK((solver.equalityMultipliers() - sol.tail(me)).lpNorm<Eigen::Infinity>() <= 1e-8 * ys);
    CHECK(solver.iterations() == 0);
    CHECK(solver.info().equality_rank == me);
  }
}

TEST_CASE("qp: degenerate and redundant constraints", "[qp]") {
  std::mt19937_64 rng(11);
  SECTION("duplicated inequality rows and rows that repeat a bound") {
    for (int seed = 0; seed < 10; ++seed) {
      RandomQpSpec spec;
      spec.n = 12;
      spec.me = 3;
      spec.mi = 10;
      QpProblem base(spec.n, spec.me, spec.mi);
      mrqp::qp::generateRandomQp(spec, rng, base);
      QpProblem p = makeProblem(spec.n, spec.me, 2 * spec.mi + spec.n);
      p.H() = base.H();
      p.g() = base.g();
      p.A() = base.A();
      p.b() = base.b();
      p.C().topRows(spec.mi) = base.C();
      p.C().middleRows(spec.mi, spec.mi) = base.C();  // every row twice
      p.l().head(2 * spec.mi) << base.l(), base.l();
      p.u().head(2 * spec.mi) << base.u(), base.u();
      p.C().bottomRows(spec.n) = Eigen::MatrixXd::Identity(spec.n, spec.n);  // the bounds again
      p.l().tail(spec.n) = base.xl();
      p.u().tail(spec.n) = base.xu();
      p.xl() = base.xl();
      p.xu() = base.xu();
      QpSolver s1(base), s2(p);
      REQUIRE(s1.solve(base) == QpStatus::Optimal);
      REQUIRE(s2.solve(p) == QpStatus::Optimal);
      CHECK((s1.x() - s2.x()).lpNorm<Eigen::Infinity>() <= 1e-8);
      CHECK(s2.objective() == Approx(s1.objective()).epsilon(1e-10));
      CHECK(qptest::kktErrors(p, s2).worst() <= 1e-8);
    }
  }
  SECTION("linearly dependent and duplicated equalities") {
    for (int seed = 0; seed < 10; ++seed) {
      RandomQpSpec spec;
      spec.n = 15;
      spec.me = 4;
      spec.mi = 8;
      QpProblem base(spec.n, spec.me, spec.mi);
      mrqp::qp::generateRandomQp(spec, rng, base);
      QpProblem p = makeProblem(spec.n, spec.me + 3, spec.mi);
      p.H() = base.H();
      p.g() = base.g();
      p.A().topRows(spec.me) = base.A();
      p.b().head(spec.me) = base.b();
      p.A().row(spec.me) = base.A().row(0);  // duplicate
      p.b()(spec.me) = base.b()(0);
      p.A().row(spec.me + 1) = 2.0 * base.A().row(1) - 0.5 * base.A().row(2);  // combination
      p.b()(spec.me + 1) = 2.0 * base.b()(1) - 0.5 * base.b()(2);
      p.A().row(spec.me + 2) = -3.0 * base.A().row(3);  // scaled
      p.b()(spec.me + 2) = -3.0 * base.b()(3);
      p.C() = base.C();
      p.l() = base.l();
      p.u() = base.u();
      p.xl() = base.xl();
      p.xu() = base.xu();
      QpSolver s1(base), s2(p);
      REQUIRE(s1.solve(base) == QpStatus::Optimal);
      REQUIRE(s2.solve(p) == QpStatus::Optimal);
      CHECK(s2.info().equality_rank == spec.me);
      CHECK(s2.info().dependent_equalities == 3);
      CHECK((s1.x() - s2.x()).lpNorm<Eigen::Infinity>() <= 1e-8);
      CHECK(qptest::kktErrors(p, s2).worst() <= 1e-8);
      // an inconsistent right-hand side on a dependent row is infeasible
      p.b()(spec.me + 1) += 1e-3;
      CHECK(s2.solve(p) == QpStatus::Infeasible);
    }
  }
  SECTION("degenerate vertex: more active constraints than variables") {
    // minimise ½‖x − (2, 2)‖² subject to x0 ≤ 1, x1 ≤ 1, x0 + x1 ≤ 2, 2x0 + x1 ≤ 3, x0 ≤ 1 (bound)
    QpProblem p = makeProblem(2, 0, 4);
    p.H().setIdentity();
    p.g() = vec({-2, -2});
    p.C() << 1, 0, 0, 1, 1, 1, 2, 1;
    p.u() = vec({1, 1, 2, 3});
    p.xu() = vec({1, inf});
    QpSolver s(p);
    REQUIRE(s.solve(p) == QpStatus::Optimal);
    CHECK((s.x() - vec({1, 1})).norm() <= 1e-12);
    CHECK(qptest::kktErrors(p, s).worst() <= 1e-12);
  }
  SECTION("rows with l == u and fixed variables act as equalities") {
    QpProblem p = makeProblem(3, 0, 2);
    p.H().setIdentity();
    p.g() = vec({1, 2, 3});
    p.C() << 1, 1, 1, 1, -1, 0;
    p.l() = vec({1, -inf});
    p.u() = vec({1, 0.5});
    p.xl() = vec({-inf, 0.25, -inf});
    p.xu() = vec({inf, 0.25, inf});
    QpSolver s(p);
    REQUIRE(s.solve(p) == QpStatus::Optimal);
    CHECK(s.info().equality_rank == 2);
    CHECK(s.x()(1) == Approx(0.25));
    CHECK(s.x().sum() == Approx(1.0));
    CHECK(qptest::kktErrors(p, s).worst() <= 1e-12);
  }
  SECTION("equalities fix every variable") {
    QpProblem p = makeProblem(2, 2, 1);
    p.H().setIdentity();
    p.A() << 1, 1, 1, -1;
    p.b() = vec({2, 0});
    p.C() << 1, 0;
    p.l() = vec({0.5});
    p.u() = vec({inf});
    QpSolver s(p);
    REQUIRE(s.solve(p) == QpStatus::Optimal);
    CHECK((s.x() - vec({1, 1})).norm() <= 1e-14);
    p.l()(0) = 1.5;  // now the row cannot hold
    CHECK(s.solve(p) == QpStatus::Infeasible);
  }
}

TEST_CASE("qp: infeasible problems are reported as such", "[qp]") {
  SECTION("bounds against an equality") {
    QpProblem p = makeProblem(2, 1, 0);
    p.H().setIdentity();
    p.A() << 1, 1;
    p.b() = vec({10});
    p.xl() = vec({0, 0});
    p.xu() = vec({1, 1});
    QpSolver s(p);
    CHECK(s.solve(p) == QpStatus::Infeasible);
  }
  SECTION("two contradictory rows") {
    QpProblem p = makeProblem(3, 0, 2);
    p.H().setIdentity();
    p.C() << 1, 1, 0, -1, -1, 0;
    p.l() = vec({2, -inf});
    p.u() = vec({inf, -3});  // x0 + x1 ≥ 2 and x0 + x1 ≥ 3: feasible
    QpSolver s(p);
    CHECK(s.solve(p) == QpStatus::Optimal);
    p.u()(1) = -3;
    p.C().row(1) << 1, 1, 0;  // x0 + x1 ≥ 2 and x0 + x1 ≤ -3
    CHECK(s.solve(p) == QpStatus::Infeasible);
  }
  SECTION("inconsistent equalities") {
    QpProblem p = makeProblem(2, 2, 0);
    p.H().setIdentity();
    p.A() << 1, 0, 1, 0;
    p.b() = vec({1, 2});
    QpSolver s(p);
    CHECK(s.solve(p) == QpStatus::Infeasible);
  }
  SECTION("a zero row that cannot hold") {
    QpProblem p = makeProblem(2, 0, 1);
    p.H().setIdentity();
    p.l() = vec({1});
    QpSolver s(p);
    CHECK(s.solve(p) == QpStatus::Infeasible);
  }
  SECTION("random problems with a row that contradicts two others") {
    std::mt19937_64 rng(5);
    int checked = 0;
    for (int seed = 0; seed < 20; ++seed) {
      RandomQpSpec spec;
      spec.n = 20;
      spec.me = 5;
      spec.mi = 15;
      spec.one_sided = 0.0;
      QpProblem base(spec.n, spec.me, spec.mi);
      mrqp::qp::generateRandomQp(spec, rng, base);
      QpProblem p = makeProblem(spec.n, spec.me, spec.mi + 1);
      p.H() = base.H();
      p.g() = base.g();
      p.A() = base.A();
      p.b() = base.b();
      p.C().topRows(spec.mi) = base.C();
      p.l().head(spec.mi) = base.l();
      p.u().head(spec.mi) = base.u();
      p.xl() = base.xl();
      p.xu() = base.xu();
      // (c0 + c1)ᵀx ≥ u0 + u1 + 0.1 contradicts c0ᵀx ≤ u0 and c1ᵀx ≤ u1
      p.C().row(spec.mi) = base.C().row(0) + base.C().row(1);
      p.l()(spec.mi) = base.u()(0) + base.u()(1) + 0.1;
      QpSolver s(p);
      CHECK(s.solve(p) == QpStatus::Infeasible);
      ++checked;
    }
    CHECK(checked == 20);
  }
}

TEST_CASE("qp: invalid input is rejected with a reason", "[qp]") {
  QpProblem p = makeProblem(3, 1, 2);
  auto reset = [&] {
    p.clear();
    p.H().setIdentity();
    p.A() << 1, 1, 1;
    p.b() << 1;
    p.C() << 1, 0, 0, 0, 1, 0;
    p.l() << 0, 0;
    p.u() << 1, 1;
  };
  QpSolver s(p);
  reset();
  REQUIRE(s.solve(p) == QpStatus::Optimal);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  auto expect = [&](QpInputError why) {
    CHECK(s.solve(p) == QpStatus::InvalidInput);
    CHECK(s.info().input_error == why);
    reset();
  };
  p.H()(1, 2) = nan;
  expect(QpInputError::NonFiniteData);
  p.g()(0) = inf;
  expect(QpInputError::NonFiniteData);
  p.A()(0, 0) = nan;
  expect(QpInputError::NonFiniteData);
  p.b()(0) = nan;
  expect(QpInputError::NonFiniteData);
  p.C()(1, 1) = -inf;
  expect(QpInputError::NonFiniteData);
  p.l()(0) = nan;
  expect(QpInputError::NonFiniteData);
  p.xu()(2) = nan;
  expect(QpInputError::NonFiniteData);
  p.l()(1) = 2;  // l > u
  expect(QpInputError::InvalidBounds);
  p.xl()(0) = 1;
  p.xu()(0) = 0;
  expect(QpInputError::InvalidBounds);
  p.l()(0) = inf;
  p.u()(0) = inf;
  expect(QpInputError::InvalidBounds);
  p.H()(0, 0) = -1;  // not convex
  expect(QpInputError::NotConvex);

  QpProblem big = makeProblem(4, 1, 2);
  big.H().setIdentity();
  CHECK(s.solve(big) == QpStatus::InvalidInput);
  CHECK(s.info().input_error == QpInputError::CapacityExceeded);
  CHECK_FALSE(p.resize(4, 1, 2));
  CHECK(p.n() == 3);
  CHECK(std::string(mrqp::qp::toString(QpStatus::Infeasible)) == "infeasible");
  CHECK(std::string(mrqp::qp::toString(QpInputError::NotConvex)) == "not-convex");
}

TEST_CASE("qp: warm start reproduces the cold solution with fewer iterations", "[qp]") {
  std::mt19937_64 rng(21);
  struct Size {
    int n, me, mi;
  };
  for (const Size& sz : {Size{20, 5, 15}, Size{60, 36, 40}, Size{150, 100, 150}}) {
    RandomQpSpec spec;
    spec.n = sz.n;
    spec.me = sz.me;
    spec.mi = sz.mi;
    QpProblem p(sz.n, sz.me, sz.mi);
    mrqp::qp::generateRandomQp(spec, rng, p);
    QpSolver warm(p), cold(p);
    cold.settings().warm_start = false;
    REQUIRE(warm.solve(p) == QpStatus::Optimal);
    long warm_iters = 0, cold_iters = 0;
    for (int step = 0; step < 20; ++step) {
      mrqp::qp::perturbQp(1e-4, rng, p);
      INFO("n " << sz.n << " step " << step);
      REQUIRE(warm.solve(p) == QpStatus::Optimal);
      REQUIRE(cold.solve(p) == QpStatus::Optimal);
      CHECK(warm.info().warm_started);
      CHECK_FALSE(warm.info().cold_restarted);
      CHECK_FALSE(cold.info().warm_started);
      CHECK((warm.x() - cold.x()).lpNorm<Eigen::Infinity>() <=
            1e-8 * std::max(1.0, cold.x().lpNorm<Eigen::Infinity>()));
      CHECK(warm.objective() == Approx(cold.objective()).epsilon(1e-10));
      CHECK(warm.iterations() <= cold.iterations());
      CHECK(qptest::kktErrors(p, warm).worst() <= 1e-8);
      warm_iters += warm.iterations();
      cold_iters += cold.iterations();
    }
    CHECK(warm_iters * 5 < cold_iters);
  }
}

TEST_CASE("qp: a failed warm start falls back to a cold start", "[qp]") {
  std::mt19937_64 rng(8);
  RandomQpSpec spec;
  spec.n = 30;
  spec.me = 8;
  spec.mi = 20;
  QpProblem q(spec.n, spec.me, spec.mi);
  mrqp::qp::generateRandomQp(spec, rng, q);
  QpSolver s(q);
  REQUIRE(s.solve(q) == QpStatus::Optimal);
  // an unrelated problem of the same size: the stale active set may not help, the answer is right
  QpSolver fresh(q);
  fresh.settings().warm_start = false;
  mrqp::qp::generateRandomQp(spec, rng, q);
  REQUIRE(s.solve(q) == QpStatus::Optimal);
  REQUIRE(fresh.solve(q) == QpStatus::Optimal);
  CHECK((s.x() - fresh.x()).lpNorm<Eigen::Infinity>() <= 1e-8);
  // an infeasible problem after an optimal one: the warm attempt fails, the cold one confirms
  REQUIRE(s.info().warm_started);
  q.xl()(0) = 5.0;
  q.xu()(0) = 6.0;
  q.A().row(0).setZero();
  q.A()(0, 0) = 1.0;
  q.b()(0) = 0.0;  // x0 = 0 and 5 ≤ x0 ≤ 6
  CHECK(s.solve(q) == QpStatus::Infeasible);
  CHECK(s.info().warm_started);
  CHECK(s.info().cold_restarted);
  // after a failure the solver still works, warm or not
  mrqp::qp::generateRandomQp(spec, rng, q);
  REQUIRE(s.solve(q) == QpStatus::Optimal);
  REQUIRE(fresh.solve(q) == QpStatus::Optimal);
  CHECK((s.x() - fresh.x()).lpNorm<Eigen::Infinity>() <= 1e-8);
  s.resetWarmStart();
  REQUIRE(s.solve(q) == QpStatus::Optimal);
  CHECK_FALSE(s.info().warm_started);
}

TEST_CASE("qp: the active size may be below capacity and change between solves", "[qp]") {
  std::mt19937_64 rng(13);
  QpProblem p(50, 20, 30);
  QpSolver s(p);
  struct Size {
    int n, me, mi;
  };
  for (const Size& sz : {Size{10, 3, 5}, Size{50, 20, 30}, Size{1, 0, 0}, Size{25, 20, 0}, Size{10, 3, 5},
                         Size{0, 0, 0}, Size{40, 0, 30}}) {
    RandomQpSpec spec;
    spec.n = sz.n;
    spec.me = sz.me;
    spec.mi = sz.mi;
    REQUIRE(mrqp::qp::generateRandomQp(spec, rng, p));
    REQUIRE(p.n() == sz.n);
    QpProblem exact(sz.n, sz.me, sz.mi);
    exact.H() = p.H();
    exact.g() = p.g();
    exact.A() = p.A();
    exact.b() = p.b();
    exact.C() = p.C();
    exact.l() = p.l();
    exact.u() = p.u();
    exact.xl() = p.xl();
    exact.xu() = p.xu();
    QpSolver reference(exact);
    INFO("n " << sz.n << " me " << sz.me << " mi " << sz.mi);
    REQUIRE(s.solve(p) == QpStatus::Optimal);
    REQUIRE(reference.solve(exact) == QpStatus::Optimal);
    REQUIRE(s.x().size() == sz.n);
    REQUIRE(s.equalityMultipliers().size() == sz.me);
    REQUIRE(s.inequalityMultipliers().size() == sz.mi);
    CHECK((s.x() - reference.x()).lpNorm<Eigen::Infinity>() <= 1e-10);
    CHECK(qptest::kktErrors(p, s).worst() <= 1e-8);
  }
}

TEST_CASE("qp: semi-definite Hessians are solved by proximal regularisation", "[qp]") {
  std::mt19937_64 rng(17);
  for (int seed = 0; seed < 12; ++seed) {
    RandomQpSpec spec;
    spec.n = 30;
    spec.me = seed % 3 == 0 ? 0 : 5;
    spec.mi = 20;
    spec.hessian_rank = seed % 4 == 0 ? 0 : 10;  // rank 0: a linear program in a box
    spec.gradient_scale = 1.0;
    QpProblem p(spec.n, spec.me, spec.mi);
    mrqp::qp::generateRandomQp(spec, rng, p);
    if (spec.hessian_rank == 0) p.g() = Eigen::VectorXd::Random(spec.n);
    QpSolver s(p);
    INFO("seed " << seed);
    REQUIRE(s.solve(p) == QpStatus::Optimal);
    CHECK(s.info().regularized);
    const auto k = qptest::kktErrors(p, s);
    CHECK(k.stationarity <= 1e-8);
    CHECK(k.primal <= 1e-8);
    CHECK(k.dual <= 1e-8);
    CHECK(k.complementarity <= 1e-8);
  }
  SECTION("an unbounded problem is not reported optimal") {
    QpProblem p = makeProblem(3, 0, 1);
    p.g() = vec({1, -1, 0});  // H = 0, x0 unbounded below
    p.C() << 0, 1, 0;
    p.u() = vec({1});
    QpSolver s(p);
    CHECK(s.solve(p) != QpStatus::Optimal);
  }
}

TEST_CASE("qp: a non-symmetric H is used through its symmetric part", "[qp]") {
  std::mt19937_64 rng(19);
  RandomQpSpec spec;
  spec.n = 12;
  spec.me = 2;
  spec.mi = 6;
  QpProblem p(spec.n, spec.me, spec.mi);
  mrqp::qp::generateRandomQp(spec, rng, p);
  QpSolver s1(p);
  REQUIRE(s1.solve(p) == QpStatus::Optimal);
  const Eigen::VectorXd x1 = s1.x();
  Eigen::MatrixXd K = Eigen::MatrixXd::Random(spec.n, spec.n);
  p.H() += K - K.transpose();  // same symmetric part
  QpSolver s2(p);
  REQUIRE(s2.solve(p) == QpStatus::Optimal);
  CHECK((s2.x() - x1).lpNorm<Eigen::Infinity>() <= 1e-10);
}

TEST_CASE("qp: the iteration budget is enforced", "[qp]") {
  std::mt19937_64 rng(23);
  RandomQpSpec spec;
  spec.n = 40;
  spec.me = 10;
  spec.mi = 40;
  QpProblem p(spec.n, spec.me, spec.mi);
  mrqp::qp::generateRandomQp(spec, rng, p);
  QpSolver s(p);
  REQUIRE(s.solve(p) == QpStatus::Optimal);
  REQUIRE(s.iterations() > 3);
  s.resetWarmStart();
  s.settings().max_iterations = 3;
  CHECK(s.solve(p) == QpStatus::IterationLimit);
  CHECK(s.iterations() <= 3);
}
