#include "problem/rigid_object.hpp"

#include <Eigen/Eigenvalues>

#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>

namespace mrqp::problem {

namespace {

Eigen::Matrix3d skew(const Eigen::Vector3d& x) noexcept {
  Eigen::Matrix3d S;
  S << 0.0, -x.z(), x.y(),  //
      x.z(), 0.0, -x.x(),   //
      -x.y(), x.x(), 0.0;
  return S;
}

/// Rotation of the (not necessarily unit) quaternion q[3..6] = (w, x, y, z), as the generated
/// models compute it.
Eigen::Matrix3d rotationOf(const Eigen::Ref<const Eigen::VectorXd>& q) noexcept {
  const double n = std::sqrt(q(3) * q(3) + q(4) * q(4) + q(5) * q(5) + q(6) * q(6));
  const double w = q(3) / n, x = q(4) / n, y = q(5) / n, z = q(6) / n;
  Eigen::Matrix3d R;
  R(0, 0) = 1 - 2 * (y * y + z * z);
  R(0, 1) = 2 * (x * y - w * z);
  R(0, 2) = 2 * (x * z + w * y);
  R(1, 0) = 2 * (x * y + w * z);
  R(1, 1) = 1 - 2 * (x * x + z * z);
  R(1, 2) = 2 * (y * z - w * x);
  R(2, 0) = 2 * (x * z - w * y);
  R(2, 1) = 2 * (y * z + w * x);
  R(2, 2) = 1 - 2 * (x * x + y * y);
  return R;
}

[[noreturn]] void reject(const std::string& name, const std::string& why) {
  throw std::invalid_argument("RigidObject '" + name + "': " + why);
}

}  // namespace

RigidObject::RigidObject(std::string name, double mass, const Eigen::Vector3d& com,
                         const Eigen::Matrix3d& inertia_about_com, std::string frame_name)
    : Entity(std::move(name), 7, 6, true), frame_name_(std::move(frame_name)) {
  double detail = 0.0;
  if (const char* why = inertiaProblem(mass, com, inertia_about_com, &detail)) {
    std::ostringstream s;
    s << why;
    if (why[std::char_traits<char>::length(why) - 1] == ' ') s << detail;
    reject(name_, s.str());
  }
  if (frame_name_.empty()) frame_name_ = name_;
  assignInertia(mass, com, 0.5 * (inertia_about_com + inertia_about_com.transpose()));

  neutral(q_);
  update();
}

const char* RigidObject::inertiaProblem(double mass, const Eigen::Vector3d& com, const Eigen::Matrix3d& Ic,
                                        double* detail) noexcept {
  *detail = mass;
  if (!std::isfinite(mass) || !(mass > 0.0)) return "mass must be finite and positive, got ";
  if (!com.allFinite()) return "centre of mass is not finite";
  if (!Ic.allFinite()) return "inertia is not finite";
  const double scale = Ic.cwiseAbs().maxCoeff();
  *detail = (Ic - Ic.transpose()).cwiseAbs().maxCoeff();
  if (*detail > 1e-9 * scale) return "inertia is not symmetric, |I - I^T| = ";
  const Eigen::Matrix3d S = 0.5 * (Ic + Ic.transpose());
  *detail = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(S, Eigen::EigenvaluesOnly).eigenvalues().minCoeff();
  if (!(*detail > 0.0)) return "inertia about the centre of mass is not positive definite, smallest eigenvalue ";
  return nullptr;
}

void RigidObject::assignInertia(double mass, const Eigen::Vector3d& com, const Eigen::Matrix3d& Ic) noexcept {
  mass_ = mass;
  c_ = com;
  Ic_ = Ic;
  const Eigen::Matrix3d C = skew(c_);
  Io_ = Ic_ - mass * C * C;  // parallel axis: I_c + m [c]×[c]×ᵀ
  I6_.topLeftCorner<3, 3>() = Io_;
  I6_.topRightCorner<3, 3>() = mass * C;
  I6_.bottomLeftCorner<3, 3>() = -mass * C;
  I6_.bottomRightCorner<3, 3>() = mass * Eigen::Matrix3d::Identity();
}

bool RigidObject::setInertia(double mass, const Eigen::Vector3d& com,
                             const Eigen::Matrix3d& inertia_about_com) noexcept {
  double detail = 0.0;
  if (inertiaProblem(mass, com, inertia_about_com, &detail) != nullptr) return false;
  assignInertia(mass, com, 0.5 * (inertia_about_com + inertia_about_com.transpose()));
  computeDynamics();
  return true;
}

bool RigidObject::setInertialParameters(const InertialParameters& phi) noexcept {
  const double m = phi(0);
  if (!std::isfinite(m) || !(m > 0.0)) return false;
  const Eigen::Vector3d c = phi.segment<3>(1) / m;
  Eigen::Matrix3d Io;
  Io << phi(4), phi(5), phi(7),  //
      phi(5), phi(6), phi(8),    //
      phi(7), phi(8), phi(9);
  const Eigen::Matrix3d C = skew(c);
  return setInertia(m, c, Io + m * C * C);  // I_c = I_O − m [c]×[c]×ᵀ
}

RigidObject::InertialParameters RigidObject::inertialParameters() const noexcept {
  InertialParameters phi;
  phi << mass_, mass_ * c_.x(), mass_ * c_.y(), mass_ * c_.z(), Io_(0, 0), Io_(0, 1), Io_(1, 1), Io_(0, 2),
      Io_(1, 2), Io_(2, 2);
  return phi;
}

const char* RigidObject::frameName(int frame) const noexcept { return frame == 0 ? frame_name_.c_str() : ""; }

int RigidObject::frameIndex(const std::string& name) const noexcept { return name == frame_name_ ? 0 : -1; }

const char* RigidObject::jointName(int /*joint*/) const noexcept { return ""; }

void RigidObject::neutral(Eigen::Ref<Eigen::VectorXd> q) const noexcept {
  q.setZero();
  q(3) = 1.0;
}

Pose RigidObject::framePose(int frame) const noexcept {
  Pose out;
  if (frame != 0) return out;
  out.R = R_;
  out.p = p_;
  return out;
}

void RigidObject::frameJacobian(int frame, const Eigen::Vector3d& point,
                                Eigen::Ref<Eigen::MatrixXd> J) const noexcept {
  J.setZero();
  if (frame != 0) return;
  // ω_world = R ω, ṗ = R (v + ω × r) = R v − R [r]× ω.
  J.topLeftCorner<3, 3>() = R_;
  J.bottomLeftCorner<3, 3>().noalias() = -R_ * skew(point);
  J.bottomRightCorner<3, 3>() = R_;
}

Vector6d RigidObject::frameBiasAcceleration(int frame, const Eigen::Vector3d& point) const noexcept {
  Vector6d out = Vector6d::Zero();
  if (frame != 0) return out;
  // With a constant body twist the angular acceleration is zero and the point accelerates by
  // ω × (v + ω × r) in object axes.
  const Eigen::Vector3d vp = u_ + w_.cross(point);
  out.tail<3>().noalias() = R_ * w_.cross(vp);
  return out;
}

void RigidObject::computeDynamics() noexcept {
  R_ = rotationOf(q_);
  p_ = q_.head<3>();
  w_ = v_.head<3>();
  u_ = v_.segment<3>(3);

  M_ = I6_;
  // h = I v; N = v ×* h − gravity wrench, all at the origin in object axes.
  Vector6d h;
  h.noalias() = I6_ * v_.head<6>();
  const Eigen::Vector3d g_b = R_.transpose() * gravity_;
  N_.head<3>() = w_.cross(h.head<3>()) + u_.cross(h.tail<3>()) - mass_ * c_.cross(g_b);
  N_.tail<3>() = w_.cross(h.tail<3>()) - mass_ * g_b;

  com_ = p_;
  com_.noalias() += R_ * c_;
  Jc_.leftCols<3>().noalias() = -R_ * skew(c_);
  Jc_.rightCols<3>() = R_;
  const Eigen::Vector3d vc = u_ + w_.cross(c_);
  com_bias_.noalias() = R_ * w_.cross(vc);
}

void RigidObject::integrateConfiguration(double dt) noexcept {
  // SE(3) exponential of the body twist (ω, v)·dt, composed on the right of the current pose.
  const Eigen::Vector3d w = v_.head<3>() * dt;
  const Eigen::Vector3d u = v_.segment<3>(3) * dt;
  const double th2 = w.squaredNorm(), th = std::sqrt(th2);
  double B, C;  // (1 − cos θ)/θ², (θ − sin θ)/θ³
  if (th < 1e-4) {
    B = 0.5 - th2 / 24.0;
    C = 1.0 / 6.0 - th2 / 120.0;
  } else {
    B = (1.0 - std::cos(th)) / th2;
    C = (th - std::sin(th)) / (th2 * th);
  }
  const Eigen::Vector3d wu = w.cross(u);
  const Eigen::Vector3d du = u + B * wu + C * w.cross(wu);
  const double n = std::sqrt(q_(3) * q_(3) + q_(4) * q_(4) + q_(5) * q_(5) + q_(6) * q_(6));
  const double qw = q_(3) / n, qx = q_(4) / n, qy = q_(5) / n, qz = q_(6) / n;
  const Eigen::Matrix3d R = rotationOf(q_);
  q_.head<3>().noalias() += R * du;
  // Quaternion of exp(ω dt): (cos θ/2, sin(θ/2)/θ · ω dt).
  const double dw = th < 1e-4 ? 1.0 - th2 / 8.0 : std::cos(0.5 * th);
  const double hs = th < 1e-4 ? 0.5 - th2 / 48.0 : std::sin(0.5 * th) / th;
  const double dx = hs * w.x(), dy = hs * w.y(), dz = hs * w.z();
  const double rw = qw * dw - qx * dx - qy * dy - qz * dz;
  const double rx = qw * dx + qx * dw + qy * dz - qz * dy;
  const double ry = qw * dy - qx * dz + qy * dw + qz * dx;
  const double rz = qw * dz + qx * dy - qy * dx + qz * dw;
  const double rn = std::sqrt(rw * rw + rx * rx + ry * ry + rz * rz);
  q_(3) = rw / rn;
  q_(4) = rx / rn;
  q_(5) = ry / rn;
  q_(6) = rz / rn;
}

}  // namespace mrqp::problem
