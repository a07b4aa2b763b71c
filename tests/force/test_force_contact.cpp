// The admittance through a contact that is free along its normal (problem/contact.hpp,
// docs/force-control.md "Contacts free along the normal"):
//   - the tests' press scene with the tool's contact with the table active and `free: [normal]`:
//     the ideal plant, a spring wall of stiffness k under the tool (force_setup.hpp), mode direct
//     with fᵈ. Along n the contact leaves the tool to the admittance's task, so the force loop is
//     the first-order loop of Sec. III: ḟ = k v = k K_I (fᵈ − f), the force error decays as
//     exp(−K_I k t) — the measured rate is fitted and compared with K_I·k; the force ends at fᵈ;
//     the contact's held directions keep the tool from moving sideways;
//   - the same contact holding its normal is refused by the force_control section (the admittance
//     could not move), as are a free normal far from the admittance's and two grasps squeezing one
//     entity along held normals;
//   - the scene file's `free:` words and their errors (FILE:LINE: FIELD).
#include <catch2/catch.hpp>

#include <cmath>
#include <string>
#include <vector>

#include "force_setup.hpp"

using forcetest::ForceSetup;
using forcetest::replaced;

namespace {

/// The press scene with its table contact active and free along its normal, mode direct, fᵈ.
std::string freeText(double force, const std::string& free = "free: [normal]") {
  std::string t = forcetest::dataText("panda_press.yaml");
  t = replaced(t, "    active: false\n", free.empty() ? std::string() : "    " + free + "\n");
  t = replaced(t, "    force: 10", "    force: " + std::to_string(force));
  return t;
}

std::string errorOf(const std::string& text) {
  try {
    ForceSetup s(text, "f.yaml");
  } catch (const std::exception& e) {
    return e.what();
  }
  return "(no error)";
}

}  // namespace

TEST_CASE("force: through a contact free along its normal the force error decays at K_I k", "[force][loop]") {
  const double fd = 40.0, k = 4000.0, KI = 5e-4;
  ForceSetup s(freeText(fd), "f.yaml");
  mrqp::problem::Entity& e = s.sc.problem->entity(0);
  e.update();
  const int tcp = e.frameIndex("panda_hand_tcp");
  const Eigen::Vector3d p0 = e.framePose(tcp).p;
  // The contact's normal in the world (the TCP's −z: about 6° off the vertical at this posture).
  const Eigen::Vector3d cn = e.framePose(tcp).R * Eigen::Vector3d(0, 0, -1);
  REQUIRE(s.sc.problem->contactActive(s.sc.contacts.at("hand_table")));
  s.plant->height = p0.z();  // touching, no force
  s.plant->stiffness = k;
  REQUIRE(s.boot());
  // log(fᵈ − f) against t while the error is between 15 % and 80 % of fᵈ (clear of the start's
  // filter delay and of the ±0.4 N steps of the loop at the end).
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  int n = 0;
  double lateral = 0.0;
  for (int c = 0; c < 4000; ++c) {
    s.cycle();
    const double err = fd - s.plant->wallForce();
    if (err < 0.8 * fd && err > 0.15 * fd) {
      const double t = s.t(), y = std::log(err);
      sx += t;
      sy += y;
      sxx += t * t;
      sxy += t * y;
      ++n;
    }
    mrqp::problem::Entity& w = s.sc.problem->entity(0);  // the controller's estimate of the state
    const Eigen::Vector3d d = w.framePose(tcp).p - p0;
    lateral = std::max(lateral, (d - cn * cn.dot(d)).norm());
  }
  REQUIRE_FALSE(s.ctrl->safeStopped());
  REQUIRE(n > 300);
  const double slope = (n * sxy - sx * sy) / (n * sxx - sx * sx);
  CHECK(-slope == Approx(KI * k).epsilon(0.1));
  // Settled on fᵈ (the loop's steps: ±0.6 N), the tool fᵈ/k into the wall.
  CHECK(s.plant->wallForce() == Approx(fd).margin(0.6));
  CHECK(s.plant->contactHeight() == Approx(p0.z() - fd / k).margin(2e-4));
  // The contact's held directions: the tool moved along the contact's normal only.
  CHECK(lateral < 1e-4);
}

TEST_CASE("force: an admittance whose contact holds its normal is refused", "[force][loop]") {
  // The table contact active, holding every direction.
  const std::string held = errorOf(freeText(10.0, ""));
  CHECK(held.rfind("f.yaml:", 0) == 0);
  CHECK(held.find("force_control[0].mode: mode 'direct' moves end-effector 'tool' along its normal, which "
                  "contact 'hand_table' holds: give the contact free: [normal]") != std::string::npos);
  // Free, but along a direction that is not the admittance's.
  std::string sideways = freeText(10.0);
  sideways = replaced(sideways, "    normal: [0, 0, -1]\n    friction: 0.7", "    normal: [1, 0, 0]\n    friction: 0.7");
  const std::string far = errorOf(sideways);
  CHECK(far.find("contact 'hand_table' is free along its normal, which is 84° from end-effector 'tool''s normal") !=
        std::string::npos);
  // Mode off all run: nothing moves, nothing to check.
  CHECK(errorOf(replaced(freeText(10.0, ""), "mode: direct", "mode: off")) == "(no error)");
  // The free contact: accepted.
  CHECK(errorOf(freeText(10.0)) == "(no error)");
}

TEST_CASE("force: two grasps squeezing one entity along held normals are refused", "[force][loop]") {
  // A second Panda and a box between the two hands, each hand's contact holding its normal.
  std::string t = forcetest::dataText("panda_press.yaml");
  t = replaced(t, "max_contact_generators: 16", "max_contact_generators: 32");
  t = replaced(t, "contacts:\n",
               "  - name: box\n    model: rigid_object\n    mass: 1.0\n    inertia: [0.01, 0.01, 0.01]\n"
               "    pose: {xyz: [0.5, 0, 0.3]}\n"
               "contacts:\n"
               "  - name: grasp\n    entity: box\n    frame: box\n    other: {entity: panda, frame: panda_hand_tcp}\n"
               "    points: [[0, 0, 0]]\n    normal: [0, 0, 1]\n");
  // Two admittances of the same hand are not allowed (one per task): the second end-effector is
  // the hand's posture-free twin, a frame_position task on the same frame.
  t = replaced(t, "tasks:\n",
               "tasks:\n  - {name: press2, type: frame_position, entity: panda, frame: panda_hand_tcp, weight: 1}\n");
  t += "  - {name: tool2, task: press2, sensor: panda_link8, normal: [0, 0, 1], normal_frame: world, mode: direct, "
       "force: 5}\n";
  const std::string err = errorOf(t);
  CHECK(err.find("force_control[1].mode: end-effectors 'tool' and 'tool2' squeeze entity 'box'") != std::string::npos);
}

TEST_CASE("force: the scene file's free words and their errors", "[force][scene]") {
  const std::string base = forcetest::dataText("panda_press.yaml");
  const auto spec = [&](const std::string& free) {
    return mrqp::scene::loadSceneString(replaced(base, "    active: false\n", "    " + free + "\n"), "s.yaml");
  };
  CHECK(spec("free: [normal]").contacts[0].free == mrqp::problem::kFreeNormal);
  CHECK(spec("free: [tangent, twist]").contacts[0].free == (mrqp::problem::kFreeTangent | mrqp::problem::kFreeTwist));
  CHECK(spec("free: [normal, tangent, twist, tilt]").contacts[0].free == mrqp::problem::kFreeAll);
  CHECK(spec("free: []").contacts[0].free == 0);
  const auto error = [&](const std::string& free) {
    try {
      spec(free);
    } catch (const std::exception& e) {
      return std::string(e.what());
    }
    return std::string("(no error)");
  };
  // The contact's `free:` is on line 30 of the file.
  CHECK(error("free: [normals]") ==
        "s.yaml:30: contacts[0].free[0]: unknown direction 'normals' (expected normal, tangent, twist, tilt)");
  CHECK(error("free: [normal, normal]") == "s.yaml:30: contacts[0].free[1]: direction 'normal' is given twice");
  CHECK(error("free: normal").rfind("s.yaml:30: contacts[0].free: ", 0) == 0);
  const std::string point =
      replaced(replaced(base, "    active: false\n", "    free: [twist]\n"),
               "points: [[0.01, 0.01, 0], [0.01, -0.01, 0], [-0.01, -0.01, 0], [-0.01, 0.01, 0]]", "points: [[0, 0, 0]]");
  try {
    mrqp::scene::loadSceneString(point, "s.yaml");
    FAIL("a rotation freed on a point contact was accepted");
  } catch (const std::exception& e) {
    CHECK(std::string(e.what()) ==
          "s.yaml:30: contacts[0].free[0]: a single-point contact holds no rotation: 'twist' does not apply "
          "(normal, tangent)");
  }
}
