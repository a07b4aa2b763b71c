// The six generated test models (tests/data/models) behind one generic face, shared by
// mrqp-model-summary and bench_model: a struct of static forwarding functions per generated
// namespace, plus a fixed pseudo-random state within the joint limits.
#pragma once

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <random>

#include "model/model_traits.hpp"
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
  MRQP_MODEL_TRAITS(NS);                                                                        \
  struct NS##_face : NS##_model {                                                               \
    static constexpr const char* name = LABEL;                                                  \
    static constexpr const char* urdf = MRQP_TOOLS_MODELS_DIR "/" FILE;                         \
    static void jacobianWorld(const Data& d, int f, Jacobian& J) {                              \
      jacobian(d, f, Eigen::Vector3d::Zero(), true, J);                                         \
    }                                                                                           \
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
    q = mrqp::model::sampleConfiguration<M>(rng);
    for (int i = 0; i < M::nv; ++i) {
      const double lim = std::min(1.0, M::vLimit()[static_cast<std::size_t>(i)]);
      v(i) = lim * u(rng);
    }
    for (int i = 0; i < M::nv; ++i) a(i) = u(rng);
  }
};

}  // namespace mrqp::tools
