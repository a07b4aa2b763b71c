// State from contact kinematics (see contact_estimator.hpp).
#include "loop/contact_estimator.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>

namespace mrqp::loop {

namespace {

problem::Pose compose(const problem::Pose& a, const problem::Pose& b) noexcept {
  problem::Pose c;
  c.R = a.R * b.R;
  c.p = a.R * b.p + a.p;
  return c;
}

problem::Pose inverse(const problem::Pose& a) noexcept {
  problem::Pose c;
  c.R = a.R.transpose();
  c.p = -(c.R * a.p);
  return c;
}

/// Rotation vector of R (world axes).
Eigen::Vector3d logRotation(const Eigen::Matrix3d& R) noexcept {
  const Eigen::AngleAxisd aa(R);
  return aa.angle() * aa.axis();
}

/// The point whose position the fit of contact d compares, in the fitted side's frame: the frame
/// origin, or for a contact that leaves every rotation free (`free: [twist, tilt]`: a point held,
/// the bodies turning about it) the centre of its points, the point the no-slip constraint holds.
/// `rel`: the surface frame in the other frame (the frozen pose).
Eigen::Vector3d heldPoint(const problem::ContactDesc& d, const problem::Pose& rel, bool surface) noexcept {
  if ((d.free & problem::kFreeRotations) != problem::kFreeRotations || d.npoints < 1)
    return Eigen::Vector3d::Zero();
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  for (int k = 0; k < d.npoints; ++k) c += d.points[static_cast<std::size_t>(k)];
  c /= static_cast<double>(d.npoints);
  return surface ? c : Eigen::Vector3d(rel.R * c + rel.p);
}

}  // namespace

ContactEstimator::ContactEstimator(problem::MultiRobotProblem& problem, const std::vector<bool>& measured,
                                   const std::vector<int>& imu_frame, int iterations,
                                   bool estimate_unmeasured)
    : p_(problem), measured_(measured), imu_frame_(imu_frame), iterations_(iterations) {
  measured_.resize(static_cast<std::size_t>(p_.entityCount()), false);
  imu_frame_.resize(static_cast<std::size_t>(p_.entityCount()), -1);
  imu_.assign(static_cast<std::size_t>(p_.entityCount()), drivers::ImuFeedback{});
  imu_fresh_.assign(static_cast<std::size_t>(p_.entityCount()), 0);
  frozen_.resize(static_cast<std::size_t>(p_.contactCapacity()));
  known_.assign(static_cast<std::size_t>(p_.entityCount()), 0);
  residual_.assign(static_cast<std::size_t>(p_.entityCount()), -1.0);
  int max_nv = 0;
  for (int e = 0; e < p_.entityCount(); ++e) max_nv = std::max(max_nv, p_.entity(e).nv());
  J_.setZero(6, max_nv);
  Jo_.setZero(6, max_nv);
  v_save_.setZero(max_nv);
  zero_.setZero(max_nv);
  filters_.assign(static_cast<std::size_t>(p_.entityCount()), BaseAttitudeFilter{});
  imu_time_.assign(static_cast<std::size_t>(p_.entityCount()), -1);
  // Floating bases of measured robots first, then everything without hardware.
  for (int pass = 0; pass < 2; ++pass) {
    for (int e = 0; e < p_.entityCount(); ++e) {
      const problem::Entity& en = p_.entity(e);
      if (pass == 0 && measured_[static_cast<std::size_t>(e)] && en.floatingBase()) {
        targets_.push_back(makeTarget(e, 0, 6));
        if (imu_frame_[static_cast<std::size_t>(e)] >= 0) {  // with an IMU also the position alone
          targets_.back().position_only = static_cast<int>(position_targets_.size());
          position_targets_.push_back(makeTarget(e, 3, 3));  // v = (ω; v) body
        }
      } else if (pass == 1 && estimate_unmeasured && !measured_[static_cast<std::size_t>(e)] && en.nv() > 0) {
        targets_.push_back(makeTarget(e, 0, en.nv()));
      }
    }
  }
}

ContactEstimator::Target ContactEstimator::makeTarget(int entity, int first, int count) {
  Target t;
  t.entity = entity;
  t.first = first;
  t.count = count;
  t.A.setZero(6 * kMaxLinks, t.count);
  t.b.setZero(6 * kMaxLinks);
  t.N.setZero(t.count, t.count);
  t.x.setZero(t.count);
  // Sizes the factorisation's storage before the cycle, and gives it a defined status (Eigen's
  // sized constructor leaves it uninitialised, and moving the object reads it).
  t.ldlt.compute(Eigen::MatrixXd::Identity(t.count, t.count));
  return t;
}

bool ContactEstimator::estimated(int entity) const noexcept {
  return residual_[static_cast<std::size_t>(entity)] >= 0.0;
}

problem::Pose ContactEstimator::targetPose(int c, bool surface_side) const noexcept {
  // Where the frozen contact puts the frame of one side, from the other side's current pose.
  const problem::ContactDesc& d = p_.contact(c);
  const Frozen& f = frozen_[static_cast<std::size_t>(c)];
  if (d.other_entity < 0) return f.rel;  // surface frame in the world
  const problem::Pose other = p_.entity(d.other_entity).framePose(d.other_frame);
  const problem::Pose surface = p_.entity(d.entity).framePose(d.frame);
  return surface_side ? compose(other, f.rel) : compose(surface, inverse(f.rel));
}

int ContactEstimator::gather(const Target& t, std::array<int, kMaxLinks>& links,
                             const std::vector<std::uint8_t>& known) const noexcept {
  int n = 0;
  for (int c = 0; c < p_.contactCapacity() && n < kMaxLinks; ++c) {
    if (!p_.contactActive(c) || !frozen_[static_cast<std::size_t>(c)].recorded) continue;
    const problem::ContactDesc& d = p_.contact(c);
    if (d.entity == t.entity) {
      if (d.other_entity < 0 || known[static_cast<std::size_t>(d.other_entity)])
        links[static_cast<std::size_t>(n++)] = c;
    } else if (d.other_entity == t.entity && known[static_cast<std::size_t>(d.entity)]) {
      links[static_cast<std::size_t>(n++)] = c;
    }
  }
  return n;
}

void ContactEstimator::applyIncrement(Target& t) noexcept {
  // q ← q ⊕ dx on the estimated coordinates (the entity's own integration, v = dx over 1 s).
  problem::Entity& e = p_.entity(t.entity);
  const int nv = e.nv();
  v_save_.head(nv) = e.v();
  e.v().setZero();
  e.v().segment(t.first, t.count) = t.x;
  e.integrate(zero_.head(nv), 1.0);
  e.v() = v_save_.head(nv);
}

void ContactEstimator::dropFree(int c, Target& t, int i) const noexcept {
  // A contact's free directions (problem/contact.hpp) hold nothing: their rows leave the fit.
  const problem::ContactDesc& d = p_.contact(c);
  if (d.free == 0) return;
  const Eigen::Matrix3d Rc = p_.entity(d.entity).framePose(d.frame).R * problem::contactFrame(d.normal);
  Eigen::Matrix3d P_lin = Eigen::Matrix3d::Identity(), P_ang = Eigen::Matrix3d::Identity();
  for (int k = 0; k < 3; ++k) {
    if (d.frees(k)) P_lin -= Rc.col(k) * Rc.col(k).transpose();
    if (d.frees(k + 3)) P_ang -= Rc.col(k) * Rc.col(k).transpose();
  }
  t.b.segment<3>(6 * i) = P_ang * t.b.segment<3>(6 * i);
  t.b.segment<3>(6 * i + 3) = P_lin * t.b.segment<3>(6 * i + 3);
  for (int j = 0; j < t.count; ++j) {
    t.A.block<3, 1>(6 * i, j) = P_ang * t.A.block<3, 1>(6 * i, j);
    t.A.block<3, 1>(6 * i + 3, j) = P_lin * t.A.block<3, 1>(6 * i + 3, j);
  }
}

void ContactEstimator::fitPose(Target& t, const std::array<int, kMaxLinks>& links, int n) noexcept {
  problem::Entity& e = p_.entity(t.entity);
  double worst = 0.0;
  for (int it = 0; it <= iterations_; ++it) {
    e.updateKinematics();
    worst = 0.0;
    for (int i = 0; i < n; ++i) {
      const int c = links[static_cast<std::size_t>(i)];
      const problem::ContactDesc& d = p_.contact(c);
      const bool surface = d.entity == t.entity;
      const int frame = surface ? d.frame : d.other_frame;
      const problem::Pose want = targetPose(c, surface);
      const problem::Pose have = e.framePose(frame);
      const Eigen::Vector3d dr = logRotation(want.R * have.R.transpose());
      const Eigen::Vector3d r = heldPoint(d, frozen_[static_cast<std::size_t>(c)].rel, surface);
      const Eigen::Vector3d dp = (want.p + want.R * r) - (have.p + have.R * r);
      worst = std::max({worst, dr.norm(), dp.norm()});
      t.b.segment<3>(6 * i) = dr;
      t.b.segment<3>(6 * i + 3) = dp;
      e.frameJacobian(frame, r, J_.leftCols(e.nv()));
      t.A.middleRows(6 * i, 6) = J_.middleCols(t.first, t.count);
      dropFree(c, t, i);
    }
    if (it == iterations_ || worst < 1e-10) break;
    const int rows = 6 * n;
    t.N.noalias() = t.A.topRows(rows).transpose() * t.A.topRows(rows);
    t.N.diagonal().array() += 1e-9;
    t.x.noalias() = t.A.topRows(rows).transpose() * t.b.head(rows);
    t.ldlt.compute(t.N);
    t.x = t.ldlt.solve(t.x);
    if (!t.x.allFinite()) break;
    applyIncrement(t);
  }
  residual_[static_cast<std::size_t>(t.entity)] = worst;
}

void ContactEstimator::fitVelocity(Target& t, const std::array<int, kMaxLinks>& links, int n) noexcept {
  // Zero relative twist at each contact frame's origin (at the held point of a contact free in
  // every rotation): J_est v_est = twist of the other side − the contribution of this entity's
  // other (measured) coordinates.
  problem::Entity& e = p_.entity(t.entity);
  const int nv = e.nv();
  for (int i = 0; i < n; ++i) {
    const int c = links[static_cast<std::size_t>(i)];
    const problem::ContactDesc& d = p_.contact(c);
    const bool surface = d.entity == t.entity;
    const int frame = surface ? d.frame : d.other_frame;
    const int other_entity = surface ? d.other_entity : d.entity;
    const int other_frame = surface ? d.other_frame : d.frame;
    const Eigen::Vector3d r = heldPoint(d, frozen_[static_cast<std::size_t>(c)].rel, surface);
    e.frameJacobian(frame, r, J_.leftCols(nv));
    Eigen::Matrix<double, 6, 1> want = Eigen::Matrix<double, 6, 1>::Zero();
    if (other_entity >= 0) {
      problem::Entity& o = p_.entity(other_entity);
      const problem::Pose of = o.framePose(other_frame);
      const problem::Pose ef = e.framePose(frame);
      const Eigen::Vector3d point = of.R.transpose() * (ef.p + ef.R * r - of.p);
      o.frameJacobian(other_frame, point, Jo_.leftCols(o.nv()));
      want.noalias() = Jo_.leftCols(o.nv()) * o.v();
    }
    t.A.middleRows(6 * i, 6) = J_.middleCols(t.first, t.count);
    // Subtract what the coordinates that are not estimated contribute.
    Eigen::Matrix<double, 6, 1> rest = J_.leftCols(nv) * e.v();
    rest.noalias() -= J_.middleCols(t.first, t.count) * e.v().segment(t.first, t.count);
    t.b.segment<6>(6 * i) = want - rest;
    dropFree(c, t, i);
  }
  const int rows = 6 * n;
  t.N.noalias() = t.A.topRows(rows).transpose() * t.A.topRows(rows);
  t.N.diagonal().array() += 1e-9;
  t.x.noalias() = t.A.topRows(rows).transpose() * t.b.head(rows);
  t.ldlt.compute(t.N);
  t.x = t.ldlt.solve(t.x);
  if (t.x.allFinite()) e.v().segment(t.first, t.count) = t.x;
}

void ContactEstimator::setImu(int entity, const drivers::ImuFeedback& sample) noexcept {
  imu_[static_cast<std::size_t>(entity)] = sample;
  imu_fresh_[static_cast<std::size_t>(entity)] = 1;
}

void ContactEstimator::fuseImu(Target& t, const std::array<int, kMaxLinks>& links, int n) noexcept {
  const auto entity = static_cast<std::size_t>(t.entity);
  problem::Entity& e = p_.entity(t.entity);
  const drivers::ImuFeedback& m = imu_[entity];
  // The reference orientation: the contacts' fit of all six base coordinates, else the IMU's
  // attitude output through the IMU frame's pose in the base (from the joints).
  if (n > 0) fitPose(t, links, n);
  e.updateKinematics();
  auto q = e.q();
  const Eigen::Quaterniond q_base(q(3), q(4), q(5), q(6));
  const Eigen::Matrix3d R_base_imu =
      q_base.toRotationMatrix().transpose() * e.framePose(imu_frame_[entity]).R;
  Eigen::Quaterniond reference = q_base;
  if (n == 0) {
    const Eigen::Quaterniond qi(m.orientation[0], m.orientation[1], m.orientation[2], m.orientation[3]);
    reference = Eigen::Quaterniond(qi.normalized().toRotationMatrix() * R_base_imu.transpose());
  }
  const Eigen::Vector3d gyro =
      R_base_imu * Eigen::Vector3d(m.angular_velocity[0], m.angular_velocity[1], m.angular_velocity[2]);
  const double period =
      imu_time_[entity] < 0
          ? 0.0
          : std::clamp(static_cast<double>(m.timestamp - imu_time_[entity]) * 1e-9, 0.0, 0.1);
  imu_time_[entity] = m.timestamp;
  BaseAttitudeFilter& f = filters_[entity];
  f.update(gyro, period, reference, n > 0);
  const Eigen::Quaterniond& qf = f.orientation();
  q(3) = qf.w();
  q(4) = qf.x();
  q(5) = qf.y();
  q(6) = qf.z();
  e.v().head<3>() = f.rate();
}

void ContactEstimator::estimate() noexcept {
  // Contacts that became active freeze their relative pose at the current state.
  bool any_new = false;
  for (int c = 0; c < p_.contactCapacity(); ++c) {
    Frozen& f = frozen_[static_cast<std::size_t>(c)];
    if (!p_.contactActive(c)) {
      f.recorded = false;
    } else if (!f.recorded) {
      any_new = true;
    }
  }
  if (any_new) {
    for (int e = 0; e < p_.entityCount(); ++e) p_.entity(e).updateKinematics();
    for (int c = 0; c < p_.contactCapacity(); ++c) {
      Frozen& f = frozen_[static_cast<std::size_t>(c)];
      if (!p_.contactActive(c) || f.recorded) continue;
      const problem::ContactDesc& d = p_.contact(c);
      const problem::Pose surface = p_.entity(d.entity).framePose(d.frame);
      f.rel = d.other_entity < 0
                  ? surface
                  : compose(inverse(p_.entity(d.other_entity).framePose(d.other_frame)), surface);
      f.recorded = true;
    }
  }
  // Measured robots are known (their joints); their bases and everything else follow.
  for (int e = 0; e < p_.entityCount(); ++e) {
    known_[static_cast<std::size_t>(e)] =
        measured_[static_cast<std::size_t>(e)] && !p_.entity(e).floatingBase() ? 1 : 0;
    residual_[static_cast<std::size_t>(e)] = -1.0;
  }
  for (Target& t : targets_) {
    std::array<int, kMaxLinks> links{};
    // The other sides' frame poses at their current (measured or estimated) state.
    for (int e = 0; e < p_.entityCount(); ++e) {
      if (known_[static_cast<std::size_t>(e)] == 1) {
        p_.entity(e).updateKinematics();
        known_[static_cast<std::size_t>(e)] = 2;  // updated
      }
    }
    const int n = gather(t, links, known_);
    Target* fit = &t;
    if (t.position_only >= 0) {
      // With an IMU: its sample fused with the contacts fixes the orientation; the position is fitted.
      if (imu_fresh_[static_cast<std::size_t>(t.entity)]) {
        fuseImu(t, links, n);
        imu_fresh_[static_cast<std::size_t>(t.entity)] = 0;
      }
      fit = &position_targets_[static_cast<std::size_t>(t.position_only)];
    }
    if (n > 0) {
      fitPose(*fit, links, n);
      // The twist from the contacts (all six coordinates: the angular velocity consistent with
      // feet that do not move), the gyro's rate only when no contact holds (set by fuseImu).
      fitVelocity(t, links, n);
    }
    known_[static_cast<std::size_t>(t.entity)] = n > 0 ? 2 : 1;  // fitted: its frame poses are current
  }
}

}  // namespace mrqp::loop
