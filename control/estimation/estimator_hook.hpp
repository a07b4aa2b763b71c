// Online inertial-parameter estimation (paper 1, Sec. IV) on the controller's cycle
// (docs/estimation.md): one loop::CycleHook that runs an InertialEstimator per entity of the
// scene's estimation section between the estimate and the QP update.
//
// On the robot cycle of the hands that hold an entity (the F/T sample's rate) it
//   - takes each hand's last fresh F/T sample (sensor axes: what the tool side exerts on the arm
//     side), removes the tool's weight and turns it into the wrench the hand applies on the
//     entity about the sensor's origin, world axes: f = m_t g − R f_s, τ = (R c_t) × m_t g − R τ_s;
//   - maps it through the entity's world-aligned Jacobian at that point: μ = Σ Jᵀ (τ; f) (eq. 51);
//     for a hand whose contact leaves directions free (the QP's model then does not tie the
//     entity to the hand along them) the point is the sensor's place in the entity's frame
//     taken at the first observation: a hand that holds what it weighs holds it rigidly;
//   - filters with second-order state-variable filters (StateVariableFilter), so that all terms
//     of Y φ = μ are delayed alike: a fixed-base entity's joint positions (the contact fit of the
//     measured joint positions) through two in cascade, q̇ and q̈ the exact derivatives of that
//     cascade (the loop's velocity of a mechanism is its plan's, not a measurement), μ through the
//     same cascade; a floating base's velocity and μ through one each (q̈ the derivative of the
//     filtered velocity), its pose used as it is;
//   - after the filter has settled, steps the InertialEstimator with (q, q̇, q̈, μ) filtered;
//   - with feed_back, writes the estimated springs (K, C, O) into the QP's model of the entity.
// It holds (no update) while a hand's sample is stale, a value is not finite, or the controller
// has stopped. The log gets, per entity, each estimated quantity and its standard deviation, the
// filter's state θ and its deviations, and the whitened regression rows of the last update (what
// the batch estimate of tools/irls needs).
//
// Set-up (the constructor) allocates and throws; onCycle is noexcept and allocation-free.
#pragma once

#include <Eigen/Core>

#include <memory>
#include <string>
#include <vector>

#include "estimation/estimation_spec.hpp"
#include "estimation/inertial_estimator.hpp"
#include "estimation/regressor_factory.hpp"
#include "estimation/state_variable_filter.hpp"
#include "loop/controller.hpp"
#include "problem/rigid_object.hpp"

namespace mrqp::estimation {

class EstimatorHook final : public loop::CycleHook {
 public:
  /// Throws std::invalid_argument when the controller does not match the spec.
  EstimatorHook(loop::Controller& controller, const EstimationSpec& spec);

  void onCycle(loop::Controller& controller, drivers::TimeNs now) noexcept override;

  int size() const noexcept { return static_cast<int>(slots_.size()); }
  const EntityEstimationSpec& spec(int i) const noexcept { return slot(i).spec; }
  const InertialEstimator& estimator(int i) const noexcept { return *slot(i).est; }
  /// Filter updates done (accepted) for entity i.
  long updates(int i) const noexcept { return slot(i).updates; }
  /// Estimates of a rigid object's parameters that the QP's model refused (feed_back).
  long feedBackRefused(int i) const noexcept { return slot(i).feed_back_refused; }
  /// The last μ (filtered) of entity i.
  const Eigen::VectorXd& lastObservation(int i) const noexcept { return slot(i).mu_f.value(); }
  /// The last filtered velocity and acceleration of entity i.
  const Eigen::VectorXd& lastVelocity(int i) const noexcept { return slot(i).v_f.value(); }
  const Eigen::VectorXd& lastAcceleration(int i) const noexcept { return slot(i).v_f.derivative(); }

  /// Estimated mass and CoM (rigid objects; NaN otherwise) and their standard deviations.
  double mass(int i) const noexcept;
  double massStd(int i) const noexcept;
  Eigen::Vector3d com(int i) const noexcept;
  /// (K, C, O) of spring s of entity i and their standard deviations.
  Eigen::Vector3d spring(int i, int s) const noexcept;
  Eigen::Vector3d springStd(int i, int s) const noexcept;

  /// The names of the filter's state θ of entity i (m, hx, hy, hz, Ixx, …; JOINT_K, …).
  const std::vector<std::string>& stateNames(int i) const noexcept { return slot(i).state_names; }
  /// The log's columns of this hook (names) and the values of the last cycle, in that order.
  const std::vector<std::string>& logColumns() const noexcept { return columns_; }
  const double* logValues() const noexcept { return values_.data(); }

 private:
  struct Slot {
    Slot(const EntityEstimationSpec& s, EntityRegressor r, int nv, int nq, double period);
    EntityEstimationSpec spec;
    EntityRegressor regressor;
    std::unique_ptr<InertialEstimator> est;
    StateVariableFilter q_f, v_f, mu_f;
    StateVariableFilter qq_f, mu_pre;  // a fixed base: the cascade's second stage of q, first of μ
    Eigen::VectorXd mu, q_use;
    Eigen::MatrixXd J;
    Eigen::VectorXd sd;  // standard deviations of the full φ (updated after each update)
    Eigen::MatrixXd BP;  // basis × P (workspace of sd)
    // The last accepted update's regression, whitened by R = L Lᵀ (L⁻¹ Y_θ, L⁻¹ μ_θ): logged
    // for the batch estimate over a run (mrqp-irls).
    Eigen::MatrixXd L, Yw;
    Eigen::VectorXd muw;
    bool accepted_now = false;
    double period = 0.0, since = 0.0;
    long updates = 0;
    long feed_back_refused = 0;           // estimates the QP's model refused (not consistent)
    problem::RigidObject* object = nullptr;  // the entity, when it is a rigid object
    Eigen::Matrix3d object_Ic = Eigen::Matrix3d::Identity();  // its scene inertia about the CoM
    int value_offset = 0;  // first of this entity's values in values_
    std::vector<std::string> state_names;
    // Per hand: whether its contact leaves directions free, and the sensor's point in the
    // entity's frame (taken once for those hands, at every observation for the others).
    std::vector<char> rigid_grasp;
    std::vector<Eigen::Vector3d> grasp_point;
    bool grasp_taken = false;
  };
  Slot& slot(int i) noexcept { return *slots_[static_cast<std::size_t>(i)]; }
  const Slot& slot(int i) const noexcept { return *slots_[static_cast<std::size_t>(i)]; }
  bool observe(loop::Controller& c, Slot& s) noexcept;
  void robotCycle(loop::Controller& c, Slot& s) noexcept;
  void writeValues(Slot& s) noexcept;
  static void updateDeviations(Slot& s) noexcept;
  static void feedBack(problem::MultiRobotProblem& p, Slot& s) noexcept;
  static Eigen::Vector3d inFrameOf(const problem::Pose& frame, const Eigen::Vector3d& world_point) noexcept;

  std::vector<std::unique_ptr<Slot>> slots_;
  std::vector<std::string> columns_;
  std::vector<double> values_;
};

}  // namespace mrqp::estimation
