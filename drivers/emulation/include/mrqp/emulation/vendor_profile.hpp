// mrqp emulation -- how strict an emulated CiA 402 drive is: the behaviours in which real drives
// differ from each other and from a forgiving emulation, each one switchable, so that a test can
// pick the "vendor" the master has to cope with.
//
// lenient() is the behaviour the emulated drive always had (every switch off, four TPDOs, the
// defaults of Options); strict() is a demanding but legal CiA 301 / CiA 402 device: two TPDOs,
// aborts for absent, read-only and out-of-range objects, the PDO rules of CiA 301, TPDOs that
// must be written with bit 30 = 1 (no RTR), a SYNC timeout of 1.5 x 0x1006 with EMCY 0x8100 and
// the error behaviour of 0x1029 (pre-operational), statusword bits 4 and 9 as drives set them,
// and an identity (0x1018) and device type (0x1000) to read. The drive's watch of the master
// (heartbeat consumer of 0x1016, RPDO timeout of 0x1400:05, with the reaction of 0x6007) is off in
// both and switched on by itself. Plain data, no allocation.
#pragma once

#include <cstdint>

namespace mrqp::emulation {

struct VendorProfile {
  /// TPDOs the drive has (1..4): the communication and mapping objects of the others do not exist
  /// (writes to them are answered with abort 0x06020000).
  std::uint8_t tpdo_count = 4;
  /// Abort writes to objects the drive does not have (0x06020000 / 0x06090011); off: acknowledge
  /// and ignore them.
  bool abort_absent = true;
  /// Abort writes to read-only objects (0x06010002); off: acknowledge and ignore them.
  bool abort_read_only = true;
  /// Abort out-of-range values: transmission types 0xF1..0xFB (reserved, 0x06090030), a
  /// communication cycle period 0x1006 below min_cycle_us (0x06090032), a producer heartbeat
  /// time below min_heartbeat_ms (0x06090032).
  bool range_checks = false;
  std::uint32_t min_cycle_us = 250;
  std::uint16_t min_heartbeat_ms = 10;
  /// CiA 301 PDO rules: mapping changed only while the PDO is disabled and its entry count is 0,
  /// mappable objects only, at most 64 bits; COB-ID changed only while disabled.
  bool pdo_rules = true;
  /// Refuse to enable a TPDO whose COB-ID has bit 30 = 0 ("RTR allowed"): abort 0x06090030.
  bool rtr_check = false;
  /// > 0: in Operational, a SYNC gap longer than this factor x 0x1006 (once SYNC has been seen)
  /// is a communication error: EMCY 0x8100 (register 0x11) and the behaviour of 0x1029:01
  /// (0 pre-operational, 1 no change, 2 stopped). 0: no SYNC monitoring.
  double sync_timeout_factor = 0.0;
  std::uint8_t comm_error_behaviour = 0;  ///< initial value of 0x1029:01
  /// A communication error also makes the CiA 402 power stage fault (Fault reaction active, then
  /// Fault, error code 0x8100), as many drives do.
  bool comm_error_fault = false;
  /// Statusword as drives set it: bit 9 (remote) while NMT operational, bit 4 (voltage enabled)
  /// only from Ready to switch on up (and during quick stop / fault reaction). Off: bit 4 always,
  /// bit 9 never.
  bool statusword_bits = false;
  /// Watch the master's heartbeat as 0x1016:1 configures it (node id in bits 16..22, consumer time
  /// in ms in bits 0..15; monitoring starts with the first heartbeat heard): silent for longer is a
  /// communication error: EMCY 0x8130 (heartbeat error), the behaviour of 0x1029:01 and the CiA 402
  /// reaction of 0x6007; the error is reset (EMCY 0x0000) when the heartbeat is back and the power
  /// stage did not fault. Off: 0x1016 is stored and never watched (the drive's old behaviour).
  bool heartbeat_consumer = false;
  /// Initial 0x1400:05, RPDO1's event timer used as its deadline (ms, 0: not watched): in
  /// Operational with the power stage in Operation enabled, no RPDO1 for longer is EMCY 0x8250
  /// (RPDO timeout) and the CiA 402 reaction of 0x6007 (the NMT state is unchanged).
  std::uint16_t rpdo_timeout_ms = 0;
  /// Initial 0x6007, the CiA 402 abort connection option code: what the power stage does on a
  /// heartbeat or RPDO timeout in Operation enabled (0 nothing, 1 fault, 2 disable voltage,
  /// 3 quick stop).
  std::uint8_t abort_connection_option = 1;
  /// Identity (0x1018:1..4) and device type (0x1000), read-only.
  std::uint32_t device_type = 0x00020192u;  ///< CiA 402 servo drive
  std::uint32_t vendor_id = 0x0000029Cu;
  std::uint32_t product_code = 0x00000402u;
  std::uint32_t revision = 0x00010000u;
  std::uint32_t serial = 0x00000001u;

  static VendorProfile lenient() noexcept { return VendorProfile{}; }
  static VendorProfile strict() noexcept {
    VendorProfile p;
    p.tpdo_count = 2;
    p.range_checks = true;
    p.rtr_check = true;
    p.sync_timeout_factor = 1.5;
    p.comm_error_behaviour = 0;
    p.comm_error_fault = false;
    p.statusword_bits = true;
    return p;
  }
};

}  // namespace mrqp::emulation
