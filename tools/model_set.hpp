// The six generated models (the runtime's three of control/model, the test models of tests/support)
// behind one generic face, shared by mrqp-model-summary and bench_model: a struct of static
// forwarding functions per generated namespace, plus a fixed pseudo-random state within the joint
// limits.
#pragma once

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <random>

#include "door_model.hpp"
#include "human_model.hpp"
#include "jvrc1_model.hpp"
#include "model/model_traits.hpp"
#include "panda_model.hpp"
#include "pendulum_model.hpp"
#include "romeo_model.hpp"

#if !defined(MRQP_MODELS_URDF_DIR) || !defined(MRQP_TEST_MODELS_DIR)
#error \
    "MRQP_MODELS_URDF_DIR (control/model/urdf) and MRQP_TEST_MODELS_DIR (tests/data/models) must be defined by the build"
#endif

namespace mrqp::tools {

/// NS: generated namespace; LABEL: short model name; DIR, FILE: folder and name of the URDF file.
#define MRQP_TOOLS_MODEL(NS, LABEL, DIR, FILE)                     \
  MRQP_MODEL_TRAITS(NS);                                           \
  struct NS##_face : NS##_model {                                  \
    static constexpr const char* name = LABEL;                     \
    static constexpr const char* urdf = DIR "/" FILE;              \
    static void jacobianWorld(const Data& d, int f, Jacobian& J) { \
      jacobian(d, f, Eigen::Vector3d::Zero(), true, J);            \
    }                                                              \
  }

MRQP_TOOLS_MODEL(door_model, "door", MRQP_MODELS_URDF_DIR, "door.urdf");
MRQP_TOOLS_MODEL(pendulum_model, "pendulum", MRQP_TEST_MODELS_DIR, "double-pendulum-continuous.urdf");
MRQP_TOOLS_MODEL(panda_model, "panda", MRQP_MODELS_URDF_DIR, "panda.urdf");
MRQP_TOOLS_MODEL(jvrc1_model, "jvrc1", MRQP_MODELS_URDF_DIR, "jvrc1.urdf");
MRQP_TOOLS_MODEL(romeo_model, "romeo", MRQP_TEST_MODELS_DIR, "romeo.urdf");
MRQP_TOOLS_MODEL(human_model, "human", MRQP_TEST_MODELS_DIR, "human-subject01-48dof.urdf");

#undef MRQP_TOOLS_MODEL

/// Calls f(Face{}) for every model, in table order.
template <class F>
void forEachModel(F&& f) {
  f(door_model_face{});
  f(pendulum_model_face{});
  f(panda_model_face{});
  f(jvrc1_model_face{});
  f(romeo_model_face{});
  f(human_model_face{});
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
