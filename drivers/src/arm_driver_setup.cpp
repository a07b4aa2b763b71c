// mrqp drivers -- arm drives: construction, validation, boot configuration list, budget (setup).
#include <cmath>
#include <string>

#include "mrqp/drivers/arm_driver.hpp"
#include "mrqp/firmware_if/arm_pdo.h"
#include "mrqp/firmware_if/canopen_ids.h"
#include "mrqp/firmware_if/objects.h"

namespace mrqp::drivers {

std::vector<SdoWrite> ArmDriver::buildWrites(const ArmDriveConfig& drive) const {
  const unsigned n = drive.node;
  std::vector<SdoWrite> writes;
  auto w = [&writes](std::uint16_t index, std::uint8_t sub, std::uint8_t size, std::uint32_t value,
                     SdoAccess access = SdoAccess::Write) {
    writes.push_back(SdoWrite{index, sub, size, value, access, 0xFFFFFFFFu});
  };
  auto check = [&writes](std::uint16_t index, std::uint8_t sub, std::uint32_t value, std::uint32_t mask) {
    writes.push_back(SdoWrite{index, sub, 4, value, SdoAccess::ReadCheck, mask});
  };
  constexpr std::uint32_t kPdoInvalid = 0x80000000u;  // COB-ID bit 31: PDO does not exist / disabled
  // COB-ID bit 30 of a TPDO: 1 = no RTR allowed (many drives refuse RTR-capable PDOs).
  const std::uint32_t no_rtr = config_.tpdo_rtr_allowed ? 0u : 0x40000000u;
  // A write that disables a PDO the drive may not have: abort 0x06020000 satisfies it too.
  const SdoAccess disable_access =
      config_.tolerate_absent_pdos ? SdoAccess::WriteUnlessAbsent : SdoAccess::Write;
  // Identity first: a wrong device is not configured at all.
  if (drive.device_type != 0u) {
    check(MRQP_FW_OBJ_DEVICE_TYPE, 0, drive.device_type, drive.device_type_mask);
  }
  if (drive.vendor_id != 0u) {
    check(MRQP_FW_OBJ_IDENTITY, 1, drive.vendor_id, 0xFFFFFFFFu);
  }
  if (drive.product_code != 0u) {
    check(MRQP_FW_OBJ_IDENTITY, 2, drive.product_code, 0xFFFFFFFFu);
  }
  if (drive.revision != 0u) {
    check(MRQP_FW_OBJ_IDENTITY, 3, drive.revision, 0xFFFFFFFFu);
  }
  w(MRQP_FW_OBJ_PRODUCER_HEARTBEAT, 0, 2, config_.producer_heartbeat_ms);
  if (config_.master_node != 0u) {
    w(MRQP_FW_OBJ_CONSUMER_HEARTBEAT, 1, 4,
      (static_cast<std::uint32_t>(config_.master_node) << 16) | config_.drive_consumer_ms);
  }
  if (config_.write_cycle_period) {
    w(MRQP_FW_OBJ_COMM_CYCLE_PERIOD, 0, 4,
      config_.comm_cycle_period_us != 0u ? config_.comm_cycle_period_us
                                         : static_cast<std::uint32_t>(config_.cycle_period / 1000));
  }
  struct Pdo {
    std::uint16_t comm;
    std::uint16_t map;
    std::uint32_t cob;
    mrqp_fw_arm_pdo which;
    bool enable;
    bool tpdo;
  };
  const Pdo pdos[] = {
      {MRQP_FW_OBJ_RPDO_COMM_BASE, MRQP_FW_OBJ_RPDO_MAP_BASE, mrqp_fw_cob_rpdo(1, n), MRQP_FW_ARM_RPDO1, true,
       false},
      {MRQP_FW_OBJ_TPDO_COMM_BASE, MRQP_FW_OBJ_TPDO_MAP_BASE, mrqp_fw_cob_tpdo(1, n), MRQP_FW_ARM_TPDO1, true,
       true},
      {static_cast<std::uint16_t>(MRQP_FW_OBJ_TPDO_COMM_BASE + 1u),
       static_cast<std::uint16_t>(MRQP_FW_OBJ_TPDO_MAP_BASE + 1u), mrqp_fw_cob_tpdo(2, n), MRQP_FW_ARM_TPDO2,
       config_.tpdo2, true},
  };
  for (const Pdo& p : pdos) {
    // CiA 301 order: disable the PDO, set the transmission type, clear the mapping, write the
    // entries, set the entry count, enable the PDO.
    const std::uint32_t cob = p.cob | (p.tpdo ? no_rtr : 0u);
    if (!p.enable) {
      w(p.comm, 1, 4, kPdoInvalid | cob, disable_access);
      continue;
    }
    w(p.comm, 1, 4, kPdoInvalid | cob);
    w(p.comm, 2, 1, MRQP_FW_PDO_TRANSMISSION_SYNC);
    if (!p.tpdo && config_.rpdo_timeout_ms != 0u) {
      w(p.comm, 5, 2, config_.rpdo_timeout_ms);  // RPDO1's event timer: its deadline
    }
    w(p.map, 0, 1, 0);
    std::uint32_t entries[4] = {0, 0, 0, 0};
    const unsigned count = mrqp_fw_arm_pdo_mapping(p.which, entries);
    for (unsigned k = 0; k < count; ++k) {
      w(p.map, static_cast<std::uint8_t>(k + 1u), 4, entries[k]);
    }
    w(p.map, 0, 1, count);
    w(p.comm, 1, 4, cob);
  }
  // TPDO3 and TPDO4 would load the bus with frames nobody reads.
  w(static_cast<std::uint16_t>(MRQP_FW_OBJ_TPDO_COMM_BASE + 2u), 1, 4,
    kPdoInvalid | no_rtr | mrqp_fw_cob_tpdo(3, n), disable_access);
  w(static_cast<std::uint16_t>(MRQP_FW_OBJ_TPDO_COMM_BASE + 3u), 1, 4,
    kPdoInvalid | no_rtr | mrqp_fw_cob_tpdo(4, n), disable_access);
  w(MRQP_FW_OBJ_MODES_OF_OPERATION, 0, 1, static_cast<std::uint8_t>(drive.mode));
  return writes;
}

std::unique_ptr<ArmDriver> ArmDriver::create(const std::vector<BusRouter*>& buses, const ArmConfig& config,
                                             std::string* error) {
  auto fail = [error](const std::string& msg) {
    if (error != nullptr) {
      *error = "arm driver: " + msg;
    }
    return std::unique_ptr<ArmDriver>();
  };
  if (buses.empty()) {
    return fail("no bus given");
  }
  for (std::size_t i = 0; i < buses.size(); ++i) {
    if (buses[i] == nullptr) {
      return fail("bus " + std::to_string(i) + " is null");
    }
  }
  if (config.drives.empty()) {
    return fail("no drive configured");
  }
  if (config.cycle_period <= 0) {
    return fail("cycle_period must be > 0");
  }
  if (config.sync_counter_overflow == 1u || config.sync_counter_overflow > 240u) {
    return fail("sync_counter_overflow must be 0 (no counter) or 2..240, not " +
                std::to_string(config.sync_counter_overflow));
  }
  if (config.feedback_missing_cycles == 0u) {
    return fail("feedback_missing_cycles must be >= 1");
  }
  if (config.producer_heartbeat_ms > 0u &&
      config.heartbeat_timeout <= milliseconds(config.producer_heartbeat_ms)) {
    return fail("heartbeat_timeout (" + std::to_string(config.heartbeat_timeout / 1000000) +
                " ms) must be longer than the producer heartbeat time (" +
                std::to_string(config.producer_heartbeat_ms) + " ms)");
  }
  if (config.master_node != 0u) {
    if (!mrqp_fw_node_valid(config.master_node)) {
      return fail("master_node " + std::to_string(config.master_node) + " is not a node id 1..127");
    }
    if (config.master_heartbeat_ms == 0u || config.drive_consumer_ms <= config.master_heartbeat_ms) {
      return fail("drive_consumer_ms must be longer than master_heartbeat_ms (> 0)");
    }
  }
  if (config.boot_timeout <= 0 || config.sdo_timeout <= 0 || config.enable_timeout <= 0 ||
      config.exit_timeout <= 0 || config.recovery_retry <= 0) {
    return fail("timeouts must be > 0");
  }
  if (!(config.sync_timeout_factor >= 1.0) || !std::isfinite(config.sync_timeout_factor)) {
    return fail("sync_timeout_factor must be a finite number >= 1");
  }
  std::vector<std::vector<bool>> used(buses.size(), std::vector<bool>(128, false));
  for (std::size_t i = 0; i < config.drives.size(); ++i) {
    const ArmDriveConfig& d = config.drives[i];
    const std::string who = "drive " + std::to_string(i) + " (node " + std::to_string(d.node) + ")";
    if (d.bus >= buses.size()) {
      return fail(who + ": bus index " + std::to_string(d.bus) + " but only " + std::to_string(buses.size()) +
                  " bus(es) given");
    }
    if (!mrqp_fw_node_valid(d.node)) {
      return fail(who + ": node id must be 1..127");
    }
    if (d.node == config.master_node) {
      return fail(who + ": node id equals master_node");
    }
    if (used[d.bus][d.node]) {
      return fail(who + ": node id used twice on bus " + std::to_string(d.bus));
    }
    used[d.bus][d.node] = true;
    if (d.mode != MRQP_FW_MODE_CSP && d.mode != MRQP_FW_MODE_CST) {
      return fail(who + ": mode " + std::to_string(d.mode) + " is neither CSP (8) nor CST (10)");
    }
    if (mrqp_fw_arm_scale_valid(&d.scale) == 0) {
      return fail(who + ": scale increments_per_rev and rated_torque_mNm must be > 0");
    }
    if (std::isnan(d.position_min) || std::isnan(d.position_max) || !(d.position_min < d.position_max)) {
      return fail(who + ": position_min must be < position_max");
    }
    if (!(d.torque_limit > 0.0) || !(d.velocity_limit > 0.0)) {
      return fail(who + ": torque_limit and velocity_limit must be > 0");
    }
  }

  std::unique_ptr<ArmDriver> p(new ArmDriver());
  p->config_ = config;
  p->buses_.resize(buses.size());
  for (BusSlot& b : p->buses_) {
    b.node_to_drive.fill(-1);
    b.sync.init(config.sync_counter_overflow);
    b.jitter.init(config.cycle_period, config.sync_timeout_factor);
  }
  p->master_heartbeat_.init(config.master_node, config.master_heartbeat_ms);
  p->drives_.resize(config.drives.size());
  for (std::size_t i = 0; i < config.drives.size(); ++i) {
    Drive& d = p->drives_[i];
    d.cfg = config.drives[i];
    p->buses_[d.cfg.bus].node_to_drive[d.cfg.node] = static_cast<std::int16_t>(i);
    p->buses_[d.cfg.bus].has_drives = true;
    d.nmt.init(d.cfg.node, config.reset, config.boot_timeout);
    d.nmt.setEcho(buses[d.cfg.bus]->bus().echoesOwn());
    d.sdo.init(d.cfg.node, p->buildWrites(d.cfg), config.sdo_timeout);
    d.heartbeat.init(config.producer_heartbeat_ms > 0u, config.heartbeat_timeout);
    d.faults.node = d.cfg.node;
  }
  if (const std::string why = p->routers_.attach(buses, *p, p->drives_.size()); !why.empty()) {
    return fail(why);
  }
  return p;
}

void ArmDriver::declareTraffic(std::size_t bus, BusBudget& budget) const {
  std::uint32_t n = 0;
  for (const Drive& d : drives_) {
    n += d.cfg.bus == bus ? 1u : 0u;
  }
  if (n == 0u) {
    return;
  }
  if (config_.produce_sync) {
    budget.addSync();
  }
  budget.addArmDrives(n, config_.tpdo2);
  if (config_.producer_heartbeat_ms > 0u) {
    budget.addHeartbeats(n, config_.producer_heartbeat_ms / 1000.0);
  }
  if (config_.master_node != 0u) {
    budget.addPeriodic("master heartbeat", 1, 1, FrameFormat::Classic, config_.master_heartbeat_ms / 1000.0);
  }
}

}  // namespace mrqp::drivers
