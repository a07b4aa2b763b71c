// The library used from ISO C99 code (c_usage.c), as firmware would use it.
#include <catch2/catch.hpp>

#include "c_usage.h"

TEST_CASE("C99 user: MIT enable frame", "[firmware_if][c]") {
  std::uint8_t b[8] = {};
  std::uint32_t id = 0;
  REQUIRE(mrqp_fw_c_enable_frame(b, &id) == 8);
  CHECK(id == 5u);
  const std::uint8_t expected[8] = {0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFC};
  for (int i = 0; i < 8; ++i) {
    CHECK(b[i] == expected[i]);
  }
}

TEST_CASE("C99 user: enabling an emulated drive through PDO frames", "[firmware_if][c]") {
  // Switch on disabled -> (shutdown) -> ready -> (switch on) -> switched on -> (enable) -> enabled.
  CHECK(mrqp_fw_c_emulated_drive_enable() == 3);
}
