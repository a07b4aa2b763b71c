// Online inertial-parameter estimation on the controller's cycle (see estimator_hook.hpp).
#include "estimation/estimator_hook.hpp"

#include <Eigen/Cholesky>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace mrqp::estimation {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

InertialVector rigidPrior(double m, const Eigen::Vector3d& c, const Eigen::Matrix3d& Ic) {
  const Eigen::Matrix3d I = Ic + m * (c.squaredNorm() * Eigen::Matrix3d::Identity() - c * c.transpose());
  InertialVector phi;
  phi << m, m * c.x(), m * c.y(), m * c.z(), I(0, 0), I(0, 1), I(1, 1), I(0, 2), I(1, 2), I(2, 2);
  return phi;
}

/// The wrench (torque about the sensor's origin; force), world axes, that a hand applies on what it
/// holds, from its F/T sample w = (force; torque), sensor axes, tool side on arm side.
problem::Vector6d handWrench(const std::array<double, 6>& w, const Eigen::Matrix3d& R, double tool_mass,
                             const Eigen::Vector3d& tool_com, const Eigen::Vector3d& g) noexcept {
  const Eigen::Vector3d f_s(w[0], w[1], w[2]), t_s(w[3], w[4], w[5]);
  const Eigen::Vector3d weight = tool_mass * g;
  problem::Vector6d out;
  out.head<3>() = (R * tool_com).cross(weight) - R * t_s;
  out.tail<3>() = weight - R * f_s;
  return out;
}

}  // namespace

EstimatorHook::Slot::Slot(const EntityEstimationSpec& s, EntityRegressor r, int nv, int nq, double T)
    : spec(s),
      regressor(std::move(r)),
      q_f(nq, T, s.cutoff_hz),
      v_f(nv, T, s.cutoff_hz),
      mu_f(nv, T, s.cutoff_hz),
      qq_f(nq, T, s.cutoff_hz),
      mu_pre(nv, T, s.cutoff_hz),
      mu(Eigen::VectorXd::Zero(nv)),
      q_use(Eigen::VectorXd::Zero(nq)),
      J(Eigen::MatrixXd::Zero(6, nv)),
      period(T) {}

EstimatorHook::EstimatorHook(loop::Controller& controller, const EstimationSpec& spec) {
  problem::MultiRobotProblem& p = controller.problem();
  const Eigen::Vector3d g = p.settings().gravity;
  const std::vector<loop::RobotIo>& robots = controller.robots();
  for (const EntityEstimationSpec& es : spec.entities) {
    const std::string what = "estimation: entity '" + es.name + "': ";
    if (es.entity < 0 || es.entity >= p.entityCount())
      throw std::invalid_argument(what + "not in the problem");
    if (es.hands.empty()) throw std::invalid_argument(what + "no hand holds it");
    problem::Entity& e = p.entity(es.entity);
    const int divisor = es.hands.front().divisor;
    for (const EstimationHandSpec& h : es.hands) {
      if (h.robot < 0 || h.robot >= static_cast<int>(robots.size()) ||
          robots[static_cast<std::size_t>(h.robot)].entity != h.robot_entity || h.sensor < 0 ||
          h.sensor >= static_cast<int>(robots[static_cast<std::size_t>(h.robot)].ft_sensors.size()))
        throw std::invalid_argument(what + "the controller has no such F/T sensor");
      if (h.divisor != divisor)
        throw std::invalid_argument(what + "its hands' robots run at different rates");
    }
    const double T = controller.period() * std::max(1, divisor);
    slots_.push_back(std::make_unique<Slot>(es, makeEntityRegressor(es.model, e, g), e.nv(), e.nq(), T));
    Slot& s = *slots_.back();
    RegressorModel& model = *s.regressor.model;
    for (const EstimationHandSpec& h : es.hands) {
      s.rigid_grasp.push_back(p.contact(h.contact).free != 0 ? 1 : 0);
      s.grasp_point.push_back(Eigen::Vector3d::Zero());
    }

    EstimatorConfig config;
    const int nb = model.bodyCount();
    for (int b = 0; b < nb; ++b) {
      config.body_prior.push_back(s.regressor.parameters[static_cast<std::size_t>(b)]);
      config.body_prior_std.push_back(InertialVector::Ones());
      config.bodies.push_back(BodyEstimate::None);
      ConsistencyBounds bounds;
      bounds.min_mass = es.min_mass;
      config.body_bounds.push_back(bounds);
    }
    if (es.estimate != BodyEstimate::None) {
      auto* obj = dynamic_cast<problem::RigidObject*>(&e);
      if (obj == nullptr)
        throw std::invalid_argument(what + "link parameters are estimated for rigid objects only");
      s.object = obj;
      s.object_Ic = obj->inertiaAboutCom();
      config.bodies[0] = es.estimate;
      config.body_prior[0] = rigidPrior(es.initial_mass, es.initial_com, obj->inertiaAboutCom());
      InertialVector sd = InertialVector::Constant(0.1);
      sd(0) = es.initial_mass_std;
      sd.segment<3>(1).setConstant(std::max(es.initial_mass, es.initial_mass_std) * es.initial_com_std);
      config.body_prior_std[0] = sd;
    }
    for (const EstimatedSpringSpec& sp : es.springs) {
      SpringEstimate se;
      se.velocity_index = sp.velocity_index;
      se.prior = sp.initial;
      se.prior_std = sp.initial_std;
      config.springs.push_back(se);
    }
    // R: the F/T noise of every hand mapped by Jᵀ at the initial state, and a floor. The filtered μ
    // has less variance but its samples are correlated over the filter's time constant, which gives
    // back about the same information per second as the raw samples: R is the raw samples' own.
    const int nv = e.nv();
    Eigen::MatrixXd R = es.observation_floor * es.observation_floor * Eigen::MatrixXd::Identity(nv, nv);
    e.update();
    for (const EstimationHandSpec& h : es.hands) {
      problem::Entity& robot = p.entity(h.robot_entity);
      robot.update();
      const Eigen::Vector3d o = robot.framePose(h.sensor_frame).p;
      e.frameJacobian(h.object_frame, inFrameOf(e.framePose(h.object_frame), o), s.J);
      Eigen::Matrix<double, 6, 1> var;
      var << Eigen::Vector3d::Constant(es.torque_noise * es.torque_noise),
          Eigen::Vector3d::Constant(es.force_noise * es.force_noise);
      R += s.J.transpose() * var.asDiagonal() * s.J;
    }
    config.observation_covariance = R;
    const Eigen::LLT<Eigen::MatrixXd> llt(R);
    if (llt.info() != Eigen::Success) throw std::invalid_argument(what + "R is not positive definite");
    s.L = llt.matrixL();
    config.process_noise_ratio = es.process_noise;
    s.est = std::make_unique<InertialEstimator>(model, config);
    s.sd = Eigen::VectorXd::Zero(s.est->parameters().size());
    s.BP = Eigen::MatrixXd::Zero(s.est->basis().rows(), s.est->basis().cols());
    updateDeviations(s);
    if (es.feed_back) feedBack(p, s);
    const Eigen::Index np = s.est->filter().estimate().size();
    s.Yw = Eigen::MatrixXd::Zero(nv, np);
    s.muw = Eigen::VectorXd::Zero(nv);
    static const char* const kBodyNames[10] = {"m", "hx", "hy", "hz", "Ixx", "Ixy", "Iyy", "Ixz", "Iyz", "Izz"};
    const int body_count = es.estimate == BodyEstimate::Mass ? 1 : es.estimate == BodyEstimate::MassCom ? 4
                         : es.estimate == BodyEstimate::Full  ? 10 : 0;
    for (int k = 0; k < body_count; ++k) s.state_names.emplace_back(kBodyNames[k]);
    for (const EstimatedSpringSpec& sp : es.springs) {
      for (const char* c : {"_K", "_C", "_O"}) s.state_names.push_back(sp.joint + c);
    }
    if (static_cast<Eigen::Index>(s.state_names.size()) != np)
      throw std::invalid_argument(what + "the filter's state does not match the section");

    // Log columns.
    s.value_offset = static_cast<int>(columns_.size());
    const std::string base = "est_" + es.name;
    if (es.estimate != BodyEstimate::None) {
      for (const char* c :
           {"_mass", "_mass_std", "_com_x", "_com_y", "_com_z", "_com_std_x", "_com_std_y", "_com_std_z"})
        columns_.push_back(base + c);
    }
    for (const EstimatedSpringSpec& sp : es.springs) {
      for (const char* c : {"_K", "_K_std", "_C", "_C_std", "_O", "_O_std"})
        columns_.push_back(base + "_" + sp.joint + c);
    }
    columns_.push_back(base + "_nis");
    columns_.push_back(base + "_updates");
    for (const std::string& n : s.state_names) columns_.push_back(base + "_theta_" + n);
    for (const std::string& n : s.state_names) columns_.push_back(base + "_theta_std_" + n);
    columns_.push_back(base + "_accepted");
    if (s.object != nullptr) columns_.push_back(base + "_model_mass");  // the QP's model (feed_back)
    for (int r = 0; r < nv; ++r) {
      const std::string row = base + "_row" + std::to_string(r) + "_";
      for (const std::string& n : s.state_names) columns_.push_back(row + n);
      columns_.push_back(row + "mu");
    }
  }
  values_.assign(columns_.size(), kNaN);
  for (auto& s : slots_) writeValues(*s);
}

Eigen::Vector3d EstimatorHook::inFrameOf(const problem::Pose& frame,
                                         const Eigen::Vector3d& world_point) noexcept {
  return frame.R.transpose() * (world_point - frame.p);
}

void EstimatorHook::updateDeviations(Slot& s) noexcept {
  const Eigen::MatrixXd& B = s.est->basis();
  s.BP.noalias() = B * s.est->filter().covariance();
  for (Eigen::Index i = 0; i < s.sd.size(); ++i)
    s.sd(i) = std::sqrt(std::max(0.0, s.BP.row(i).dot(B.row(i))));
}

void EstimatorHook::feedBack(problem::MultiRobotProblem& p, Slot& s) noexcept {
  problem::Entity& e = p.entity(s.spec.entity);
  const Eigen::VectorXd& phi = s.est->parameters();
  // A rigid object's (projected, physically consistent) parameters: the QP plans with them. With
  // mass or mass_com the inertia about the CoM is the scene's (what the filter does not estimate;
  // its state keeps the inertia about the origin instead, which a moving CoM would shrink about the
  // CoM); with full, all ten. An estimate the object refuses (an inertia about the CoM not positive
  // definite) leaves the model at the last one it took.
  if (s.object != nullptr) {
    const bool ok = s.spec.estimate == BodyEstimate::Full
                        ? s.object->setInertialParameters(phi.head<10>())
                        : s.object->setInertia(phi(0), phi.segment<3>(1) / phi(0), s.object_Ic);
    if (!ok) ++s.feed_back_refused;
  }
  const Eigen::Index first = phi.size() - 3 * static_cast<Eigen::Index>(s.spec.springs.size());
  for (std::size_t k = 0; k < s.spec.springs.size(); ++k) {
    const Eigen::Index at = first + 3 * static_cast<Eigen::Index>(k);
    problem::JointSpring js;
    js.stiffness = phi(at);
    js.damping = phi(at + 1);
    js.offset = phi(at + 2);
    (void)e.setSpring(s.spec.springs[k].velocity_index, js);
  }
}

double EstimatorHook::mass(int i) const noexcept {
  const Slot& s = slot(i);
  return s.spec.estimate == BodyEstimate::None ? kNaN : s.est->parameters()(0);
}

double EstimatorHook::massStd(int i) const noexcept {
  const Slot& s = slot(i);
  return s.spec.estimate == BodyEstimate::None ? kNaN : s.sd(0);
}

Eigen::Vector3d EstimatorHook::com(int i) const noexcept {
  const Slot& s = slot(i);
  if (s.spec.estimate == BodyEstimate::None) return Eigen::Vector3d::Constant(kNaN);
  const Eigen::VectorXd& phi = s.est->parameters();
  return phi.segment<3>(1) / phi(0);
}

Eigen::Vector3d EstimatorHook::spring(int i, int k) const noexcept {
  const Slot& s = slot(i);
  const Eigen::VectorXd& phi = s.est->parameters();
  const Eigen::Index at = phi.size() - 3 * static_cast<Eigen::Index>(s.spec.springs.size()) + 3 * k;
  return phi.segment<3>(at);
}

Eigen::Vector3d EstimatorHook::springStd(int i, int k) const noexcept {
  const Slot& s = slot(i);
  const Eigen::Index at = s.sd.size() - 3 * static_cast<Eigen::Index>(s.spec.springs.size()) + 3 * k;
  return s.sd.segment<3>(at);
}

bool EstimatorHook::observe(loop::Controller& c, Slot& s) noexcept {
  problem::MultiRobotProblem& p = c.problem();
  const problem::Entity& e = p.entity(s.spec.entity);
  const Eigen::Vector3d& g = p.settings().gravity;
  s.mu.setZero();
  std::size_t k = 0;
  for (const EstimationHandSpec& h : s.spec.hands) {
    const loop::RobotIo& robot = c.robots()[static_cast<std::size_t>(h.robot)];
    if (robot.ft_sensors[static_cast<std::size_t>(h.sensor)].stale != 0u) return false;
    const problem::Pose sensor = p.entity(h.robot_entity).framePose(h.sensor_frame);
    const problem::Vector6d w =
        handWrench(robot.wrench[static_cast<std::size_t>(h.sensor)], sensor.R, h.tool_mass, h.tool_com, g);
    // Along a contact's free directions the QP's model lets the entity move relative to the hand
    // (docs/estimation.md, box_mass): the lever arm of such a hand is the one of the grasp.
    Eigen::Vector3d& point = s.grasp_point[k];
    if (!s.grasp_taken || s.rigid_grasp[k] == 0) point = inFrameOf(e.framePose(h.object_frame), sensor.p);
    e.frameJacobian(h.object_frame, point, s.J);
    s.mu.noalias() += s.J.transpose() * w;
    ++k;
  }
  s.grasp_taken = true;
  return s.mu.allFinite() && e.q().allFinite() && e.v().allFinite();
}

void EstimatorHook::robotCycle(loop::Controller& c, Slot& s) noexcept {
  if (c.safeStopped() || !observe(c, s)) return;
  const problem::Entity& e = c.problem().entity(s.spec.entity);
  if (e.floatingBase()) {
    s.v_f.step(e.v());
    s.mu_f.step(s.mu);
    s.q_use = e.q();  // a pose: used as it is (docs/estimation.md)
  } else {
    // Joint positions through two filters in cascade; q̇ is the first stage's derivative through
    // the second (= the cascade's derivative), q̈ that one's derivative; μ through the same cascade.
    s.q_f.step(e.q());
    s.qq_f.step(s.q_f.value());
    s.v_f.step(s.q_f.derivative());
    s.mu_pre.step(s.mu);
    s.mu_f.step(s.mu_pre.value());
    s.q_use = s.qq_f.value();
  }
  s.since += s.period;
  if (s.since < s.spec.settle_s) return;
  if (s.est->update(s.q_use, s.v_f.value(), s.v_f.derivative(), s.mu_f.value())) {
    ++s.updates;
    s.accepted_now = true;
    s.Yw = s.est->lastRegressor();
    s.muw = s.est->lastObservation();
    s.L.triangularView<Eigen::Lower>().solveInPlace(s.Yw);
    s.L.triangularView<Eigen::Lower>().solveInPlace(s.muw);
    updateDeviations(s);
    if (s.spec.feed_back) feedBack(c.problem(), s);
  }
}

void EstimatorHook::writeValues(Slot& s) noexcept {
  double* out = values_.data() + s.value_offset;
  const Eigen::VectorXd& phi = s.est->parameters();
  if (s.spec.estimate != BodyEstimate::None) {
    *out++ = phi(0);
    *out++ = s.sd(0);
    for (int k = 0; k < 3; ++k) *out++ = phi(1 + k) / phi(0);
    // CoM deviation ≈ σ(h) / m (the mass's share neglected).
    for (int k = 0; k < 3; ++k) *out++ = s.sd(1 + k) / phi(0);
  }
  const Eigen::Index first = phi.size() - 3 * static_cast<Eigen::Index>(s.spec.springs.size());
  for (std::size_t k = 0; k < s.spec.springs.size(); ++k) {
    for (Eigen::Index j = 0; j < 3; ++j) {
      const Eigen::Index at = first + 3 * static_cast<Eigen::Index>(k) + j;
      *out++ = phi(at);
      *out++ = s.sd(at);
    }
  }
  *out++ = s.est->filter().lastNis();
  *out++ = static_cast<double>(s.updates);
  const Eigen::VectorXd& theta = s.est->filter().estimate();
  const Eigen::MatrixXd& P = s.est->filter().covariance();
  for (Eigen::Index k = 0; k < theta.size(); ++k) *out++ = theta(k);
  for (Eigen::Index k = 0; k < theta.size(); ++k) *out++ = std::sqrt(std::max(0.0, P(k, k)));
  *out++ = s.accepted_now ? 1.0 : 0.0;
  s.accepted_now = false;
  if (s.object != nullptr) *out++ = s.object->mass();
  for (Eigen::Index r = 0; r < s.Yw.rows(); ++r) {
    for (Eigen::Index k = 0; k < s.Yw.cols(); ++k) *out++ = s.Yw(r, k);
    *out++ = s.muw(r);
  }
}

void EstimatorHook::onCycle(loop::Controller& c, drivers::TimeNs) noexcept {
  for (auto& sp : slots_) {
    Slot& s = *sp;
    const auto divisor = static_cast<std::uint64_t>(std::max(1, s.spec.hands.front().divisor));
    if (c.cycles() % divisor == 0u) robotCycle(c, s);
    writeValues(s);
  }
}

}  // namespace mrqp::estimation
