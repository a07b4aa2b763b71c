// The link part of eq. 51 for one manipulated entity: Y_links(q, v, a) with Y_links φ_links equal
// to the generalised force the environment applies (gravity folded in). Implemented over a
// generated model (GeneratedRegressorModel) and over a free rigid body (FreeBodyRegressorModel).
#pragma once

#include <Eigen/Core>

namespace mrqp::estimation {

class RegressorModel {
 public:
  virtual ~RegressorModel() = default;
  /// Velocity coordinates (the rows of Y).
  virtual int velocityCount() const noexcept = 0;
  /// Bodies whose 10 parameters are columns of Y (10 · bodyCount() columns).
  virtual int bodyCount() const noexcept = 0;
  /// Y_links at (q, v, a); Y is velocityCount() × 10·bodyCount(). Allocation-free.
  virtual void linkRegressor(const Eigen::Ref<const Eigen::VectorXd>& q,
                             const Eigen::Ref<const Eigen::VectorXd>& v,
                             const Eigen::Ref<const Eigen::VectorXd>& a,
                             Eigen::Ref<Eigen::MatrixXd> Y) noexcept = 0;
};

/// A generated model's `regressor()` (all its bodies; body 0 of a fixed-base model is the world
/// and its columns are zero). `Model` is the generated namespace wrapped by a traits struct with
/// the members used below (see model/model_traits.hpp).
template <class Traits>
class GeneratedRegressorModel final : public RegressorModel {
 public:
  explicit GeneratedRegressorModel(const Eigen::Vector3d& gravity) : Y_(Traits::nv, 10 * Traits::nbodies) {
    data_.gravity = gravity;
  }
  int velocityCount() const noexcept override { return Traits::nv; }
  int bodyCount() const noexcept override { return Traits::nbodies; }
  void linkRegressor(const Eigen::Ref<const Eigen::VectorXd>& q, const Eigen::Ref<const Eigen::VectorXd>& v,
                     const Eigen::Ref<const Eigen::VectorXd>& a,
                     Eigen::Ref<Eigen::MatrixXd> Y) noexcept override {
    q_ = q;
    v_ = v;
    a_ = a;
    Traits::regressor(data_, q_, v_, a_, Y_);
    Y = Y_;
  }

 private:
  typename Traits::Data data_;
  typename Traits::ConfigVector q_;
  typename Traits::TangentVector v_, a_;
  typename Traits::Regressor Y_;
};

/// A free rigid body (RigidObject's coordinates: q = (p; w x y z), v = body twist (ω; v) in body
/// axes, a = v̇): Y = rigidBodyRegressor(v, a − (0; Rᵀ g)).
class FreeBodyRegressorModel final : public RegressorModel {
 public:
  explicit FreeBodyRegressorModel(const Eigen::Vector3d& gravity) : gravity_(gravity) {}
  int velocityCount() const noexcept override { return 6; }
  int bodyCount() const noexcept override { return 1; }
  void linkRegressor(const Eigen::Ref<const Eigen::VectorXd>& q, const Eigen::Ref<const Eigen::VectorXd>& v,
                     const Eigen::Ref<const Eigen::VectorXd>& a,
                     Eigen::Ref<Eigen::MatrixXd> Y) noexcept override;

 private:
  Eigen::Vector3d gravity_;
};

}  // namespace mrqp::estimation
