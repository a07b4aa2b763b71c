// mrqp drivers -- CANopen master, what the master's faults mean in words (CiA 301 / CiA 402):
// SDO aborts with their code, CiA 301 meaning, object and node; EMCY codes; NMT states.
//
// nmtStateStr() is real-time safe (a static string); the describe_ functions build text for
// logs and reports and allocate: call them outside the control cycle (after update(), from the
// fault report that the driver publishes).
#pragma once

#include <cstdint>
#include <string>

namespace mrqp::drivers {

/// "boot-up", "stopped", "operational", "pre-operational"; "none" for 0xFF, "invalid" otherwise.
const char* nmtStateStr(std::uint8_t state) noexcept;

/// "SDO abort 0x06020000 (object does not exist in the object dictionary) writing 0x1802:01 of
/// node 3"; `what` is "writing" or "reading".
std::string describeSdoAbort(std::uint32_t code, std::uint16_t index, std::uint8_t subindex,
                             std::uint8_t node, const char* what = "writing");

/// "EMCY 0x8100 (communication) register 0x11 from node 3".
std::string describeEmcy(std::uint16_t code, std::uint8_t error_register, std::uint8_t node);

/// "0x1018:01 of node 3 is 0x00000100, the configuration expects 0x0000029C (mask 0xFFFFFFFF)".
std::string describeCheckMismatch(std::uint16_t index, std::uint8_t subindex, std::uint8_t node,
                                  std::uint32_t expected, std::uint32_t actual, std::uint32_t mask);

}  // namespace mrqp::drivers
