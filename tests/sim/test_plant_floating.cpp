// The MuJoCo plant's floating base against the generated JVRC-1 model (44 joints, 10 of them
// mimic joints, free-flyer root): M and bias at random states, after mapping the problem's
// velocities (ω; v body twist, independent joints) to MuJoCo's (world linear velocity, local
// angular velocity, every joint). This proves the free joint's conventions, the joint order and
// the mimic joints in one comparison.
#include <catch2/catch.hpp>

#include <cmath>
#include <random>

#include "model/model_traits.hpp"
#include "sim_scenes.hpp"

using mrqp::sim::testing::makePlant;
using mrqp::sim::testing::registry;

TEST_CASE("MuJoCo plant: JVRC-1's M and bias equal the generated floating-base model's", "[sim]") {
  auto plant = makePlant(
      "entities: [{name: jvrc, model: jvrc1, pose: {xyz: [0, 0, 1]}}]\n"
      "plant: {timestep: 0.001}\n");
  const int e = plant->entityHandle("jvrc");
  std::unique_ptr<mrqp::problem::Entity> model = registry().make("jvrc1", "jvrc");
  const int nv = model->nv(), nq = model->nq();
  REQUIRE(model->floatingBase());
  REQUIRE(plant->entityNv(e) == nv);
  REQUIRE(plant->entityNq(e) == nq);
  const mjModel* m = plant->model();
  const int nmj = m->nv;
  const auto& mimics = plant->mjcf().entities.at(0).mimics;
  REQUIRE(nmj == nv + static_cast<int>(mimics.size()));
  const int free_dof = m->jnt_dofadr[mj_name2id(m, mjOBJ_JOINT, "jvrc/root")];

  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<mjtNum> full(static_cast<std::size_t>(nmj * nmj));
  for (int trial = 0; trial < 10; ++trial) {
    Eigen::VectorXd q(nq), v(nv);
    Eigen::Vector4d quat(u(rng), u(rng), u(rng), u(rng));
    quat.normalize();
    q.head<3>() << u(rng), u(rng), 1.0 + u(rng);
    q.segment<4>(3) = quat;
    for (int k = 6; k < nv; ++k) {
      double lo = model->qLower()(k), hi = model->qUpper()(k);
      if (!std::isfinite(lo) || !std::isfinite(hi)) {
        lo = -1.0;
        hi = 1.0;
      }
      q(model->qIndexOfV(k)) = lo + (hi - lo) * 0.5 * (u(rng) + 1.0);
    }
    for (int k = 0; k < nv; ++k) v(k) = u(rng);
    plant->setEntityState(e, q, v);
    model->q() = q;
    model->v() = v;
    model->update();

    // qvel_mj = T v: free joint (R v_body; ω), the joints through their handles, the mimic ones
    // with their multipliers.
    const Eigen::Matrix3d R = Eigen::Quaterniond(quat(0), quat(1), quat(2), quat(3)).toRotationMatrix();
    Eigen::MatrixXd T = Eigen::MatrixXd::Zero(nmj, nv);
    T.block<3, 3>(free_dof, 3) = R;
    T.block<3, 3>(free_dof + 3, 0).setIdentity();
    for (int k = 0; k < nv - 6; ++k) {
      const int h = plant->jointHandle("jvrc", model->jointName(k));
      REQUIRE(h >= 0);
      T(plant->jointDof(h), 6 + k) = 1.0;
    }
    for (const mrqp::sim::MjcfMimic& mm : mimics) {
      const int master = model->jointIndex(mm.master);
      REQUIRE(master >= 0);
      T(m->jnt_dofadr[mj_name2id(m, mjOBJ_JOINT, ("jvrc/" + mm.joint).c_str())], master) = mm.multiplier;
    }
    // d/dt (R v_body) = R (ω × v_body) + R v̇_body: the bias gains M_mj Ṫ v.
    Eigen::VectorXd Tdot_v = Eigen::VectorXd::Zero(nmj);
    Tdot_v.segment<3>(free_dof) = R * v.head<3>().cross(v.segment<3>(3));

    mj_fullM(m, full.data(), plant->data()->qM);
    const Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>> Mmj(
        full.data(), nmj, nmj);
    const Eigen::Map<const Eigen::VectorXd> bmj(plant->data()->qfrc_bias, nmj);
    const Eigen::MatrixXd M = T.transpose() * Mmj * T;
    const Eigen::VectorXd bias = T.transpose() * (bmj + Mmj * Tdot_v);
    const double m_err = (M - model->massMatrix()).cwiseAbs().maxCoeff();
    const double b_err = (bias - model->bias()).cwiseAbs().maxCoeff();
    INFO("trial " << trial << ": |ΔM| " << m_err << " (max |M| " << model->massMatrix().cwiseAbs().maxCoeff()
                  << "), |Δbias| " << b_err << " (max |bias| " << model->bias().cwiseAbs().maxCoeff() << ")");
    CHECK(m_err < 1e-7);
    CHECK(b_err < 1e-6);
  }
}
