// The estimation section of a scene file: door_estimate.yaml resolved (the spring joint, the hand's
// F/T sensor and contact, R from the plant's F/T noise, the truth from the scene's spring), and
// bad sections refused with FILE:LINE: FIELD: message.
#include <catch2/catch.hpp>

#include <string>

#include "estimation_loop_setup.hpp"

using namespace mrqp;

namespace {

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const std::size_t at = text.find(from);
  REQUIRE(at != std::string::npos);
  text.replace(at, from.size(), to);
  return text;
}

/// The error of reading `text`'s estimation section ("" when it reads).
std::string errorOf(const std::string& text) {
  try {
    esttest::EstimationSetup s(text, "d.yaml");
  } catch (const std::exception& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST_CASE("The estimation section of door_estimate.yaml", "[estimation][yaml]") {
  const std::string text = esttest::sceneText("door_estimate.yaml");
  esttest::EstimationSetup s(text, "door_estimate.yaml");
  REQUIRE(s.est.present);
  REQUIRE(s.est.entities.size() == 1);
  const estimation::EntityEstimationSpec& e = s.est.entities[0];
  CHECK(e.name == "door");
  CHECK(e.model == "door");
  CHECK(e.estimate == estimation::BodyEstimate::None);
  REQUIRE(e.springs.size() == 1);
  CHECK(e.springs[0].joint == "handle");
  CHECK(e.springs[0].velocity_index == 1);
  CHECK(e.springs[0].initial.isApprox(Eigen::Vector3d(1.0, 0.0, 0.0)));
  CHECK(e.springs[0].truth.isApprox(Eigen::Vector3d(3.0, 0.8, 0.4)));
  REQUIRE(e.hands.size() == 1);
  CHECK(e.hands[0].divisor == 4);
  CHECK(e.hands[0].tool_mass == Approx(0.76));
  CHECK(e.force_noise == Approx(0.2));
  CHECK(e.torque_noise == Approx(0.01));
  CHECK(e.feed_back);
}

TEST_CASE("Bad estimation sections are refused with file, line and field", "[estimation][yaml]") {
  const std::string text = esttest::sceneText("door_estimate.yaml");
  CHECK_THAT(errorOf(replaced(text, "  - entity: door\n    springs", "  - entity: dor\n    springs")),
             Catch::Contains("d.yaml:") && Catch::Contains("estimation[0].entity: unknown entity 'dor'"));
  CHECK_THAT(errorOf(replaced(text, "{joint: handle, initial", "{joint: handel, initial")),
             Catch::Contains("estimation[0].springs[0].joint: entity 'door' has no joint 'handel'"));
  CHECK_THAT(errorOf(replaced(text, "{contact: grip_top, sensor", "{contact: grip, sensor")),
             Catch::Contains("estimation[0].hands[0].contact: unknown contact 'grip'"));
  CHECK_THAT(errorOf(replaced(text, "sensor: panda_link8, tool_mass", "sensor: panda_link7, tool_mass")),
             Catch::Contains(
                 "estimation[0].hands[0].sensor: entity 'panda' has no F/T sensor on frame 'panda_link7'"));
  CHECK_THAT(
      errorOf(replaced(text, "    cutoff: 1.0", "    cutoff: 200")),
      Catch::Contains("estimation[0].cutoff: the cutoff 200 Hz is not below half the F/T rate (250 Hz)"));
  CHECK_THAT(errorOf(replaced(text, "    cutoff: 1.0", "    estimate: mass")),
             Catch::Contains("estimation[0].estimate: link parameters are estimated for rigid objects only"));
  CHECK_THAT(errorOf(replaced(text, "    cutoff: 1.0", "    estimate: heavy")),
             Catch::Contains("estimation[0].estimate: expected mass, mass_com, full or none"));
  CHECK_THAT(errorOf(replaced(text, "std: [5.0, 2.0, 2.0]", "std: [5.0, 0.0, 2.0]")),
             Catch::Contains("estimation[0].springs[0].std: expected three positive standard deviations"));
  CHECK_THAT(errorOf(replaced(text, "    cutoff: 1.0", "    cutof: 2.0")),
             Catch::Contains("estimation[0].cutof: unknown key"));
}
