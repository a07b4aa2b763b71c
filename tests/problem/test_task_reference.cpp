// Time-varying task references (eq. 26 with ġʳᵉᶠ, g̈ʳᵉᶠ): a frame position task on an actuated
// point mass (three prismatic joints x, y, z, no gravity, no limits: the QP's q̈ is the task's
// desired acceleration, the loop's integrateSolution() the ideal double integrator) follows
// pʳᵉᶠ(t) = a (1 − cos ωt) along x.
//
// With the velocity and acceleration references fed forward the error obeys ë + D ė + K e = 0
// from e(0) = ė(0) = 0: it stays zero up to the O(Δt) of the discrete integration (the
// semi-implicit Euler step q⁺ = q + (q̇ + q̈Δt)Δt is ahead of the exact one by q̈Δt²/2 per step,
// which the PD holds to below the reference's velocity amplitude times Δt, a ω Δt). With the
// set-point only (ġʳᵉᶠ = g̈ʳᵉᶠ = 0) it obeys ë + D ė + K e = −(p̈ʳᵉᶠ + D ṗʳᵉᶠ), whose steady
// state lags with amplitude a ω √(ω² + D²) / √((K − ω²)² + D² ω²).
//
// Also: a constraint kind written outside the problem (an equality row) plugs in through the
// Constraint interface.
#include <catch2/catch.hpp>

#include <cmath>
#include <memory>
#include <vector>

#include "loop/solution_integrator.hpp"
#include "problem/constraint.hpp"
#include "problem/multi_robot_problem.hpp"
#include "problem/tasks/frame_position_task.hpp"

using namespace mrqp::problem;
using mrqp::qp::QpStatus;

namespace {

constexpr double kA = 0.1, kW = 2.0, kK = 100.0, kD = 20.0, kDt = 0.001;

/// A point mass on three actuated prismatic joints (x, y, z): M = m I, N = −m g, one frame at the
/// point, J = [0; I], J̇ q̇ = 0.
class PointMass final : public Entity {
 public:
  explicit PointMass(double m) : Entity("point", 3, 3, false) {
    mass_ = m;
    setAllJointsActuated(true);
  }
  int frameCount() const noexcept override { return 1; }
  const char* frameName(int f) const noexcept override { return f == 0 ? "point" : ""; }
  int frameIndex(const std::string& n) const noexcept override { return n == "point" ? 0 : -1; }
  const char* jointName(int j) const noexcept override {
    static const char* const names[] = {"x", "y", "z"};
    return j >= 0 && j < 3 ? names[j] : "";
  }
  void neutral(Eigen::Ref<Eigen::VectorXd> q) const noexcept override { q.setZero(); }
  Pose framePose(int /*frame*/) const noexcept override {
    Pose P;
    P.p = q_;
    return P;
  }
  void frameJacobian(int /*frame*/, const Eigen::Vector3d& /*point*/,
                     Eigen::Ref<Eigen::MatrixXd> J) const noexcept override {
    J.setZero();
    J.bottomRows<3>().setIdentity();
  }
  Vector6d frameBiasAcceleration(int /*frame*/, const Eigen::Vector3d& /*point*/) const noexcept override {
    return Vector6d::Zero();
  }

 protected:
  void computeDynamics() noexcept override {
    M_ = mass_ * Eigen::Matrix3d::Identity();
    N_ = -mass_ * gravity_;
    com_ = q_;
    Jc_.setIdentity();
    com_bias_.setZero();
  }
  void integrateConfiguration(double dt) noexcept override { q_ += v_ * dt; }
};

std::unique_ptr<MultiRobotProblem> freeBody() {
  std::vector<std::unique_ptr<Entity>> es;
  es.push_back(std::make_unique<PointMass>(2.0));
  ProblemSettings s;
  s.dt = kDt;
  s.gravity.setZero();
  s.max_tasks = 2;
  s.max_constraints = 1;
  s.max_constraint_rows = 0;
  s.max_constraint_equalities = 1;
  s.regularisation = 1e-9;
  return std::make_unique<MultiRobotProblem>(std::move(es), s);
}

/// Largest |x error| over the last period of a 10 s run.
double trackingError(bool feed_forward) {
  auto p = freeBody();
  auto task = std::make_unique<FramePositionTask>(0, 0, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero());
  task->setWeight(1e4);
  task->setGains(kK, kD);
  const int id = p->addTask(std::move(task));
  REQUIRE(id >= 0);
  const double duration = 10.0, period = 2.0 * M_PI / kW;
  const int cycles = static_cast<int>(std::lround(duration / kDt));
  double worst = 0.0;
  for (int k = 0; k <= cycles; ++k) {
    const double t = k * kDt;
    const Eigen::Vector3d pos(kA * (1.0 - std::cos(kW * t)), 0.0, 0.0);
    const Eigen::Vector3d vel(kA * kW * std::sin(kW * t), 0.0, 0.0);
    const Eigen::Vector3d acc(kA * kW * kW * std::cos(kW * t), 0.0, 0.0);
    if (feed_forward) {
      REQUIRE(p->setTaskReference(id, pos, vel, acc));
    } else {
      REQUIRE(p->setTaskTarget(id, pos));
    }
    REQUIRE(p->update() == UpdateStatus::Ok);
    if (t >= duration - period) worst = std::max(worst, std::abs(p->taskError(id)(0)));
    REQUIRE(p->solve() == QpStatus::Optimal);
    mrqp::loop::integrateSolution(*p, kDt);
  }
  return worst;
}

/// q̈ of one coordinate of one entity set by an equality row: x_col = value.
class FixAcceleration final : public Constraint {
 public:
  FixAcceleration(int entity, int coordinate, double value)
      : entity_(entity), coord_(coordinate), value_(value) {}
  const char* kind() const noexcept override { return "fix_acceleration"; }
  int inequalityRows() const noexcept override { return 0; }
  int equalityRows() const noexcept override { return 1; }
  const char* check(const MultiRobotProblem& p) const noexcept override {
    return entity_ >= 0 && entity_ < p.entityCount() && coord_ >= 0 && coord_ < p.entity(entity_).nv()
               ? nullptr
               : "no such coordinate";
  }
  void update(const MultiRobotProblem& p, ConstraintRows& rows) noexcept override {
    rows.A(0, p.velocityOffset(entity_) + coord_) = 1.0;
    rows.b(0) = value_;
  }

 private:
  int entity_, coord_;
  double value_;
};

}  // namespace

TEST_CASE("Fed-forward references track a moving target; a set-point lags as the PD closed form says",
          "[problem][task]") {
  const double lag = trackingError(false);
  const double tracked = trackingError(true);
  const double closed_form =
      kA * kW * std::sqrt(kW * kW + kD * kD) / std::sqrt((kK - kW * kW) * (kK - kW * kW) + kD * kD * kW * kW);
  INFO("set-point lag " << lag << " (closed form " << closed_form << "), fed forward " << tracked);
  CHECK(lag == Approx(closed_form).epsilon(0.01));
  CHECK(tracked < kA * kW * kDt);
}

TEST_CASE("A task's references are checked for size and finiteness", "[problem][task]") {
  auto p = freeBody();
  const int id =
      p->addTask(std::make_unique<FramePositionTask>(0, 0, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()));
  REQUIRE(id >= 0);
  CHECK(p->task(id).referenceRows() == 3);
  CHECK_FALSE(p->setTaskReference(id, Eigen::VectorXd::Zero(2), Eigen::VectorXd::Zero(3)));
  CHECK_FALSE(p->setTaskReference(id, Eigen::VectorXd::Constant(3, NAN), Eigen::VectorXd::Zero(3)));
  CHECK(p->setTaskReference(id, Eigen::VectorXd::Ones(3), Eigen::VectorXd::Zero(3)));
  CHECK(p->task(id).velocityReference() == Eigen::Vector3d::Ones());
  CHECK_FALSE(p->setTaskReference(id + 1, Eigen::VectorXd::Ones(3), Eigen::VectorXd::Zero(3)));  // no task
}

TEST_CASE("A constraint kind defined outside the problem adds its equality rows", "[problem][constraint]") {
  auto p = freeBody();
  // Only the regularisation acts: without the constraint q̈ = 0.
  const int id = p->addConstraint(std::make_unique<FixAcceleration>(0, 1, 0.25));  // y of the point
  REQUIRE(id >= 0);
  CHECK(p->addConstraint(std::make_unique<FixAcceleration>(0, 9, 1.0)) == -1);  // no coordinate 9
  CHECK(p->addConstraint(std::make_unique<FixAcceleration>(0, 2, 1.0)) == -1);  // rows over capacity
  REQUIRE(p->update() == UpdateStatus::Ok);
  CHECK(p->qp().me() == 1);
  REQUIRE(p->solve() == QpStatus::Optimal);
  CHECK(p->acceleration(0)(1) == Approx(0.25).margin(1e-12));
  CHECK(p->acceleration(0).norm() == Approx(0.25).margin(1e-12));
  CHECK(p->removeConstraint(id));
  REQUIRE(p->update() == UpdateStatus::Ok);
  CHECK(p->qp().me() == 0);
  CHECK(p->restoreConstraint(id));
  REQUIRE(p->update() == UpdateStatus::Ok);
  CHECK(p->qp().me() == 1);
}
