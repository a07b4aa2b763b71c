// A generated model namespace (docs/model_gen.md) behind one generic face: MRQP_MODEL_TRAITS(ns)
// defines struct ns_model with the model's types and static forwarding functions, so that code
// written once as a template (tests, benchmarks, the problem assembly) takes a model as a type.
#pragma once

#include <Eigen/Core>

#include <cmath>
#include <random>

#define MRQP_MODEL_TRAITS(NS)                                                                             \
  struct NS##_model {                                                                                     \
    static constexpr int nq = NS::nq, nv = NS::nv, nbodies = NS::nbodies, nframes = NS::nframes;          \
    static constexpr int njoints = NS::njoints, nparams = NS::nparams;                                    \
    static constexpr bool floating_base = NS::floating_base;                                              \
    using Data = NS::Data;                                                                                \
    using ConfigVector = NS::ConfigVector;                                                                \
    using TangentVector = NS::TangentVector;                                                              \
    using MassMatrix = NS::MassMatrix;                                                                    \
    using Jacobian = NS::Jacobian;                                                                        \
    using ComJacobian = NS::ComJacobian;                                                                  \
    using Regressor = NS::Regressor;                                                                      \
    using ParamVector = NS::ParamVector;                                                                  \
    using Pose = NS::Pose;                                                                                \
    using ReferenceFrame = NS::ReferenceFrame;                                                            \
    static const auto& jointNames() { return NS::joint_names; }                                           \
    static const auto& frameNames() { return NS::frame_names; }                                           \
    static const auto& bodyNames() { return NS::body_names; }                                             \
    static const auto& frameBody() { return NS::frame_body; }                                             \
    static const auto& qLower() { return NS::q_lower; }                                                   \
    static const auto& qUpper() { return NS::q_upper; }                                                   \
    static const auto& vLimit() { return NS::v_limit; }                                                   \
    static const auto& effortLimit() { return NS::effort_limit; }                                         \
    static double totalMass() { return NS::totalMass(); }                                                 \
    static int frameIndex(const char* n) { return NS::frameIndex(n); }                                    \
    static void neutral(ConfigVector& q) { NS::neutral(q); }                                              \
    static void integrate(const ConfigVector& q, const TangentVector& v, double dt, ConfigVector& o) {    \
      NS::integrate(q, v, dt, o);                                                                         \
    }                                                                                                     \
    static void fk(Data& d, const ConfigVector& q) { NS::forwardKinematics(d, q); }                       \
    static void fk(Data& d, const ConfigVector& q, const TangentVector& v) {                              \
      NS::forwardKinematics(d, q, v);                                                                     \
    }                                                                                                     \
    static Pose framePose(const Data& d, int f) { return NS::framePose(d, f); }                           \
    static void jacobian(const Data& d, int f, const Eigen::Vector3d& p, bool world, Jacobian& J) {       \
      NS::frameJacobian(d, f, p, world ? ReferenceFrame::WorldAligned : ReferenceFrame::Local, J);        \
    }                                                                                                     \
    static NS::Motion bias(const Data& d, int f, const Eigen::Vector3d& p, bool world) {                  \
      return NS::frameBiasAcceleration(d, f, p,                                                           \
                                       world ? ReferenceFrame::WorldAligned : ReferenceFrame::Local);     \
    }                                                                                                     \
    static Eigen::Vector3d com(const Data& d) { return NS::centerOfMass(d); }                             \
    static void comJacobian(Data& d, ComJacobian& J) { NS::comJacobian(d, J); }                           \
    static void crba(Data& d, const ConfigVector& q, MassMatrix& M) { NS::crba(d, q, M); }                \
    static void nle(Data& d, const ConfigVector& q, const TangentVector& v, TangentVector& N) {           \
      NS::nonLinearEffects(d, q, v, N);                                                                   \
    }                                                                                                     \
    static void rnea(Data& d, const ConfigVector& q, const TangentVector& v, const TangentVector& a,      \
                     TangentVector& t) {                                                                  \
      NS::rnea(d, q, v, a, t);                                                                            \
    }                                                                                                     \
    static void regressor(Data& d, const ConfigVector& q, const TangentVector& v, const TangentVector& a, \
                          Regressor& Y) {                                                                 \
      NS::regressor(d, q, v, a, Y);                                                                       \
    }                                                                                                     \
    static void params(ParamVector& p) { NS::inertialParameters(p); }                                     \
  }

namespace mrqp::model {

/// A configuration drawn uniformly within the joint limits (±3 where a joint is unlimited); a
/// floating base gets a position in [−1, 1]³ and a uniformly random unit quaternion.
template <class M, class Rng>
typename M::ConfigVector sampleConfiguration(Rng& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::normal_distribution<double> n(0.0, 1.0);
  typename M::ConfigVector q;
  M::neutral(q);
  int first = 0;
  if (M::floating_base) {
    for (int i = 0; i < 3; ++i) q(i) = u(rng);
    Eigen::Vector4d quat(n(rng), n(rng), n(rng), n(rng));
    quat.normalize();
    for (int i = 0; i < 4; ++i) q(3 + i) = quat(i);
    first = 7;
  }
  for (int i = first; i < M::nq; ++i) {
    double lo = M::qLower()[static_cast<std::size_t>(i)], hi = M::qUpper()[static_cast<std::size_t>(i)];
    if (!std::isfinite(lo) || !std::isfinite(hi)) {
      lo = -3.0;
      hi = 3.0;
    }
    q(i) = lo + (hi - lo) * 0.5 * (u(rng) + 1.0);
  }
  return q;
}

}  // namespace mrqp::model
