// The generated model of a robot whose names are hostile but follow the name rule
// (tests/data/bad_urdf/hostile_names_accepted.urdf: names that end comments, close string literals,
// hold trigraphs and backslashes around code that would create /tmp/mrqp-gen-injected), compiled
// into this program by the build: nothing injected ran, every name reads back exactly as the loader
// read it, and the kinematics are those of the same robot with plain names (hostile_names_benign.urdf).
#include <catch2/catch.hpp>

#include <cstring>
#include <filesystem>
#include <random>
#include <string>

#include "benign_names_model.hpp"
#include "hostile_names_model.hpp"
#include "urdf_loader.hpp"

namespace h = hostile_names_model;
namespace b = benign_names_model;

namespace {

const std::string kBad = std::string(MRQP_TEST_DATA_DIR) + "/bad_urdf/";

}  // namespace

TEST_CASE("hostile model: the code the names would inject did not run", "[model_gen][hostile]") {
  // static initialisers of this program (the generated model is linked in) have run by now
  CHECK_FALSE(std::filesystem::exists("/tmp/mrqp-gen-injected"));
}

TEST_CASE("hostile model: every name reads back as the loader read it", "[model_gen][hostile]") {
  const auto tree = mrqp::gen::loadUrdfFile(kBad + "hostile_names_accepted.urdf", {});
  REQUIRE(h::nframes == static_cast<int>(tree.frames.size()));
  REQUIRE(h::nbodies == static_cast<int>(tree.bodies.size()));
  REQUIRE(h::njoints == static_cast<int>(tree.joint_names.size()));
  for (int f = 0; f < h::nframes; ++f) {
    const std::string& name = tree.frames[static_cast<std::size_t>(f)].name;
    CHECK(name == h::frame_names[static_cast<std::size_t>(f)]);
    CHECK(h::frameIndex(name.c_str()) == f);
  }
  for (int i = 0; i < h::nbodies; ++i)
    CHECK(tree.bodies[static_cast<std::size_t>(i)].name == h::body_names[static_cast<std::size_t>(i)]);
  for (int i = 0; i < h::njoints; ++i)
    CHECK(tree.joint_names[static_cast<std::size_t>(i)] == h::joint_names[static_cast<std::size_t>(i)]);
  REQUIRE(h::ncollision == 1);
  CHECK(std::strcmp(h::collision_shapes[0].link, "upper arm \\") == 0);
}

TEST_CASE("hostile model: the same kinematics and dynamics as the plain-named robot",
          "[model_gen][hostile]") {
  STATIC_REQUIRE(h::nq == b::nq);
  STATIC_REQUIRE(h::nv == b::nv);
  STATIC_REQUIRE(h::nframes == b::nframes);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  h::Data hd;
  b::Data bd;
  h::MassMatrix hM;
  b::MassMatrix bM;
  for (int trial = 0; trial < 20; ++trial) {
    h::ConfigVector q;
    h::TangentVector v, a;
    for (int i = 0; i < h::nq; ++i) q(i) = u(rng);
    for (int i = 0; i < h::nv; ++i) {
      v(i) = u(rng);
      a(i) = u(rng);
    }
    h::forwardKinematics(hd, q);
    b::forwardKinematics(bd, q);
    for (int f = 0; f < h::nframes; ++f) {
      const h::Pose hp = h::framePose(hd, f);
      const b::Pose bp = b::framePose(bd, f);
      CHECK((hp.p - bp.p).norm() == 0.0);
      CHECK((hp.R - bp.R).norm() == 0.0);
    }
    h::crba(hd, q, hM);
    b::crba(bd, q, bM);
    CHECK((hM - bM).norm() == 0.0);
    h::TangentVector htau, btau;
    h::rnea(hd, q, v, a, htau);
    b::rnea(bd, q, v, a, btau);
    CHECK((htau - btau).norm() == 0.0);
  }
  // and the motion is not trivial: the tool moves with the shoulder
  h::ConfigVector q0 = h::ConfigVector::Zero(), q1 = q0;
  q1(0) = 0.5;
  h::forwardKinematics(hd, q0);
  const Eigen::Vector3d p0 = h::framePose(hd, h::nframes - 1).p;
  h::forwardKinematics(hd, q1);
  CHECK((h::framePose(hd, h::nframes - 1).p - p0).norm() > 0.1);
}
