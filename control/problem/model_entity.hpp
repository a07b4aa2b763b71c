// An Entity backed by a generated model (control/model/model_traits.hpp): fixed-size work space
// inside, dynamic-size views outside. Header-only because it is a template over the model.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "model/model_traits.hpp"
#include "problem/entity.hpp"

namespace mrqp::problem {

template <class Model>
class ModelEntity final : public Entity {
 public:
  explicit ModelEntity(std::string name)
      : Entity(std::move(name), Model::nq, Model::nv, Model::floating_base) {
    typename Model::ConfigVector q0;
    Model::neutral(q0);
    q_ = q0;
    for (int k = Model::floating_base ? 6 : 0; k < Model::nv; ++k) {
      const auto iq = static_cast<std::size_t>(Model::floating_base ? k + 1 : k);
      const auto iv = static_cast<std::size_t>(k);
      q_lower_(k) = Model::qLower()[iq];
      q_upper_(k) = Model::qUpper()[iq];
      v_limit_(k) = Model::vLimit()[iv];
      effort_limit_(k) = Model::effortLimit()[iv];
    }
    mass_ = Model::totalMass();
    // Body masses and CoM positions (body frame) for the CoM bias acceleration.
    typename Model::ParamVector phi;
    Model::params(phi);
    for (int b = 0; b < Model::nbodies; ++b) {
      const auto ib = static_cast<std::size_t>(b);
      body_frame_[ib] = Model::frameIndex(Model::bodyNames()[ib]);
      body_mass_[ib] = phi(10 * b);
      body_com_[ib] = body_mass_[ib] > 0.0
                          ? Eigen::Vector3d(phi.template segment<3>(10 * b + 1) / body_mass_[ib])
                          : Eigen::Vector3d::Zero();
    }
    // Passive where the model says the joint has no effort (a door hinge), actuated otherwise.
    for (int k = Model::floating_base ? 6 : 0; k < Model::nv; ++k) {
      actuated_[static_cast<std::size_t>(k)] = effort_limit_(k) > 0.0 ? 1 : 0;
    }
  }

  int frameCount() const noexcept override { return Model::nframes; }
  const char* frameName(int f) const noexcept override {
    return f >= 0 && f < Model::nframes ? Model::frameNames()[static_cast<std::size_t>(f)] : "";
  }
  int frameIndex(const std::string& n) const noexcept override { return Model::frameIndex(n.c_str()); }
  const char* jointName(int j) const noexcept override {
    return j >= 0 && j < nv_ - jointOffset() ? Model::jointNames()[static_cast<std::size_t>(j)] : "";
  }
  void neutral(Eigen::Ref<Eigen::VectorXd> q) const noexcept override {
    typename Model::ConfigVector q0;
    Model::neutral(q0);
    q = q0;
  }

  Pose framePose(int f) const noexcept override {
    const auto P = Model::framePose(d_, f);
    Pose out;
    if (floating_) {  // the base pose is in q
      out.R = P.R;
      out.p = P.p;
      return out;
    }
    out.R.noalias() = base_.R * P.R;
    out.p.noalias() = base_.R * P.p;
    out.p += base_.p;
    return out;
  }

  void frameJacobian(int f, const Eigen::Vector3d& point,
                     Eigen::Ref<Eigen::MatrixXd> J) const noexcept override {
    Model::jacobian(d_, f, point, true, J_);
    if (floating_) {
      J = J_;
    } else {
      J.template topRows<3>().noalias() = base_.R * J_.template topRows<3>();
      J.template bottomRows<3>().noalias() = base_.R * J_.template bottomRows<3>();
    }
  }

  Vector6d frameBiasAcceleration(int f, const Eigen::Vector3d& point) const noexcept override {
    const Vector6d a = Model::bias(d_, f, point, true);
    if (floating_) return a;
    Vector6d out;
    out.template head<3>().noalias() = base_.R * a.template head<3>();
    out.template tail<3>().noalias() = base_.R * a.template tail<3>();
    return out;
  }

 private:
  void computeKinematics() noexcept override {
    // Gravity in the model's own world: the base frame of a fixed-base entity.
    d_.gravity.noalias() = floating_ ? gravity_ : Eigen::Vector3d(base_.R.transpose() * gravity_);
    qf_ = q_;
    vf_ = v_;
    Model::fk(d_, qf_, vf_);
  }
  void computeDynamics() noexcept override {
    computeKinematics();
    Model::crba(d_, qf_, Mf_);
    Model::nle(d_, qf_, vf_, Nf_);
    M_ = Mf_;
    N_ = Nf_;
    Model::comJacobian(d_, Jcf_);
    const Eigen::Vector3d c = Model::com(d_);
    Eigen::Vector3d cb = Eigen::Vector3d::Zero();
    if (mass_ > 0.0) {
      for (std::size_t b = 0; b < static_cast<std::size_t>(Model::nbodies); ++b) {
        if (body_mass_[b] > 0.0 && body_frame_[b] >= 0) {
          cb += body_mass_[b] * Model::bias(d_, body_frame_[b], body_com_[b], true).template tail<3>();
        }
      }
      cb /= mass_;
    }
    if (floating_) {
      com_ = c;
      Jc_ = Jcf_;
      com_bias_ = cb;
    } else {
      com_.noalias() = base_.R * c;
      com_ += base_.p;
      Jc_.noalias() = base_.R * Jcf_;
      com_bias_.noalias() = base_.R * cb;
    }
  }

  void integrateConfiguration(double dt) noexcept override {
    qf_ = q_;
    vf_ = v_;
    typename Model::ConfigVector out;
    Model::integrate(qf_, vf_, dt, out);
    q_ = out;
  }

  mutable typename Model::Data d_;
  mutable typename Model::Jacobian J_;
  typename Model::ConfigVector qf_;
  typename Model::TangentVector vf_, Nf_;
  typename Model::MassMatrix Mf_;
  typename Model::ComJacobian Jcf_;
  std::array<int, Model::nbodies> body_frame_{};
  std::array<double, Model::nbodies> body_mass_{};
  std::array<Eigen::Vector3d, Model::nbodies> body_com_{};
};

}  // namespace mrqp::problem
