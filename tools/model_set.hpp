// The six generated test models (tests/data/models) behind one generic face, shared by
// mrqp-model-summary and bench_model: a struct of static forwarding functions per generated
// namespace, plus a fixed pseudo-random state within the joint limits.
#pragma once

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <random>

#include "model_door.hpp"
#include "model_human.hpp"
#include "model_jvrc1.hpp"
#include "model_panda.hpp"
#include "model_pendulum.hpp"
#include "model_romeo.hpp"

#ifndef MRQP_TOOLS_MODELS_DIR
#error "MRQP_TOOLS_MODELS_DIR (folder of the test URDF files) must be defined by the build"
#endif

namespace mrqp::tools {

/// NS: generated namespace; LABEL: short model name; FILE: URDF file in MRQP_TOOLS_MODELS_DIR.
#define MRQP_TOOLS_MODEL(NS, LABEL, FILE)                                                       \
  struct NS##_face {                                                                            \
    static constexpr const char* name = LABEL;                                                  \
    static constexpr const char* urdf = MRQP_TOOLS_MODELS_DIR "/" FILE;                         \
    static constexpr int nq = NS::nq, nv = NS::nv, njoints = NS::njoints;                       \
    static constexpr int nbodies = NS::nbodies, nframes = NS::nframes, nparams = NS::nparams;   \
    static constexpr bool floating_base = NS::floating_base;                                    \
    using Data = NS::Data;                                                                      \
    using ConfigVector = NS::ConfigVector;                                                      \
    using TangentVector = NS::TangentVector;                                                    \
    using MassMatrix = NS::MassMatrix;                                                          \
    using Jacobian = NS::Jacobian;                                                              \
    using Regressor = NS::Regressor;                                                            \
    using ParamVector = NS::ParamVector;                                                        \
    static const auto& qLower() { return NS::q_lower; }                                         \
    static const auto& qUpper() { return NS::q_upper; }                                         \
    static const auto& vLimit() { return NS::v_limit; }                                         \
    static double totalMass() { return NS::totalMass(); }                                       \
    static void neutral(ConfigVector& q) { NS::neutral(q); }                                    \
    static void fk(Data& d, const ConfigVector& q) { NS::forwardKinematics(d, q); }             \
    static void jacobianWorld(const Data& d, int f, Jacobian& J) {                              \
      NS::frameJacobian(d, f, Eigen::Vector3d::Zero(), NS::ReferenceFrame::WorldAligned, J);    \
    }                                                                                           \
    static void crba(Data& d, const ConfigVector& q, MassMatrix& M) { NS::crba(d, q, M); }      \
    static void rnea(Data& d, const ConfigVector& q, const TangentVector& v,                   \
                     const TangentVector& a, TangentVector& tau) {                              \
      NS::rnea(d, q, v, a, tau);                                                                \
    }                                                                                           \
    static void regressor(Data& d, const ConfigVector& q, const TangentVector& v,              \
                          const TangentVector& a, Regressor& Y) {                               \
      NS::regressor(d, q, v, a, Y);                                                             \
    }                                                                                           \
    static void params(ParamVector& phi) { NS::inertialParameters(phi); }                       \
  }

MRQP_TOOLS_MODEL(model_door, "door", "door.urdf");
MRQP_TOOLS_MODEL(model_pendulum, "pendulum", "double-pendulum-continuous.urdf");
MRQP_TOOLS_MODEL(model_panda, "panda", "panda.urdf");
MRQP_TOOLS_MODEL(model_jvrc1, "jvrc1", "jvrc1.urdf");
MRQP_TOOLS_MODEL(model_romeo, "romeo", "romeo.urdf");
MRQP_TOOLS_MODEL(model_human, "human", "human-subject01-48dof.urdf");

#undef MRQP_TOOLS_MODEL

/// Calls f(Face{}) for every model, in table order.
template <class F>
void forEachModel(F&& f) {
  f(model_door_face{});
  f(model_pendulum_face{});
  f(model_panda_face{});
  f(model_jvrc1_face{});
  f(model_romeo_face{});
  f(model_human_face{});
}

inline constexpr int kModelCount = 6;

/// Moving URDF joints (independent + mimic). After merging, every body but the root one hangs on
/// exactly one moving joint, so this is nbodies - 1; bench_model checks it against the URDF.
template <class M>
constexpr int movingJoints() {
  return M::nbodies - 1;
}

/// A fixed pseudo-random state (q, v, a): joints uniform within their position limits
/// ([-3, 3] where a limit is infinite), base position in [-1, 1]^3 with a random unit
/// quaternion, velocities in [-1, 1] clipped to the velocity limits, accelerations in [-1, 1].
template <class M>
struct State {
  typename M::ConfigVector q;
  typename M::TangentVector v, a;

  explicit State(unsigned seed = 12345) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    M::neutral(q);
    int first = 0;
    if (M::floating_base) {
      for (int i = 0; i < 3; ++i) q(i) = u(rng);
      Eigen::Vector4d quat(u(rng), u(rng), u(rng), u(rng));
      quat.normalize();
      for (int i = 0; i < 4; ++i) q(3 + i) = quat(i);
      first = 7;
    }
    for (int i = first; i < M::nq; ++i) {
      double lo = M::qLower()[i], hi = M::qUpper()[i];
      if (!std::isfinite(lo) || !std::isfinite(hi)) {
        lo = -3.0;
        hi = 3.0;
      }
      q(i) = lo + (hi - lo) * 0.5 * (u(rng) + 1.0);
    }
    for (int i = 0; i < M::nv; ++i) {
      const double lim = std::min(1.0, M::vLimit()[i]);
      v(i) = lim * u(rng);
    }
    for (int i = 0; i < M::nv; ++i) a(i) = u(rng);
  }
};

}  // namespace mrqp::tools
