// mrqp drivers -- the drive side of the CiA 402 arm protocol (see emulated_cia402_drive.hpp).
#include "mrqp/emulation/emulated_cia402_drive.hpp"

#include "mrqp/firmware_if/canopen_ids.h"
#include "mrqp/firmware_if/emcy.h"
#include "mrqp/firmware_if/objects.h"
#include "mrqp/firmware_if/sdo.h"

namespace mrqp::emulation {

namespace {
constexpr std::uint32_t kPdoInvalid = 0x80000000u;  // COB-ID bit 31: PDO does not exist / disabled
constexpr std::uint32_t kNoRtr = 0x40000000u;       // COB-ID bit 30: no RTR allowed
constexpr std::uint32_t kAckIgnore = 1u;            // not an abort code: acknowledge, store nothing

TimeNs ms(std::uint32_t v) noexcept { return static_cast<TimeNs>(v) * 1000000; }
}  // namespace

void EmulatedCia402Drive::Host::onNmtReset(bool) noexcept {}

void EmulatedCia402Drive::send(mrqp_fw_frame f, TimeNs at, bool pdo) noexcept {
  if (silent_) {
    return;
  }
  if (pdo && corrupt_left_ > 0u) {
    --corrupt_left_;
    f.len = static_cast<std::uint8_t>(f.len - 1u);  // one byte short: the master's unpack rejects it
  }
  host_.emit(f, at);
}

EmulatedCia402Drive::EmulatedCia402Drive(Host& host, const Options& options) noexcept
    : host_(host), options_(options) {
  resetOd(false);
  boot_at_ = options_.boot_delay;  // power-on: initialisation, then the boot-up message
}

void EmulatedCia402Drive::resetOd(bool communication_only) noexcept {
  const std::uint32_t n = options_.node;
  const Entry comm[] = {
      {0x1000, 0, 4, false, options_.profile.device_type},  // device type: CiA 402 drive
      {0x1006, 0, 4, true, 0},                              // communication cycle period
      {0x1016, 0, 1, false, 1},                             // consumer heartbeat: one entry
      {0x1016, 1, 4, true, 0},
      {0x1017, 0, 2, true, 0},           // producer heartbeat time
      {0x1400, 1, 4, true, 0x200u + n},  // RPDO1: valid by default...
      {0x1400, 2, 1, true, 0xFF},
      {0x1400, 5, 2, true, options_.profile.rpdo_timeout_ms},  // RPDO1 event timer: its deadline
      {0x1600, 0, 1, true, 1},                                 // ... mapping only the controlword
      {0x1600, 1, 4, true, 0x60400010u},
      {0x1600, 2, 4, true, 0},
      {0x1600, 3, 4, true, 0},
      {0x1600, 4, 4, true, 0},
      {0x1800, 1, 4, true, 0x180u + n},  // TPDO1: valid, asynchronous, statusword only
      {0x1800, 2, 1, true, 0xFF},
      {0x1801, 1, 4, true, kPdoInvalid | (0x280u + n)},
      {0x1801, 2, 1, true, 0xFF},
      {0x1802, 1, 4, true, 0x380u + n},  // TPDO3/4 valid by default: must be disabled
      {0x1802, 2, 1, true, 0xFF},
      {0x1803, 1, 4, true, 0x480u + n},
      {0x1803, 2, 1, true, 0xFF},
      {0x1A00, 0, 1, true, 1},
      {0x1A00, 1, 4, true, 0x60410010u},
      {0x1A00, 2, 4, true, 0},
      {0x1A00, 3, 4, true, 0},
      {0x1A00, 4, 4, true, 0},
      {0x1A01, 0, 1, true, 0},
      {0x1A01, 1, 4, true, 0},
      {0x1A01, 2, 4, true, 0},
      {0x1A01, 3, 4, true, 0},
      {0x1A01, 4, 4, true, 0},
      {0x1018, 0, 1, false, 4},  // identity
      {0x1018, 1, 4, false, options_.profile.vendor_id},
      {0x1018, 2, 4, false, options_.profile.product_code},
      {0x1018, 3, 4, false, options_.profile.revision},
      {0x1018, 4, 4, false, options_.profile.serial},
      {0x1029, 0, 1, false, 1},  // error behaviour: communication error
      {0x1029, 1, 1, true, options_.profile.comm_error_behaviour},
  };
  const Entry app[] = {
      {0x6040, 0, 2, true, 0},  // controlword: an SDO write drives the state machine too
      {0x6060, 0, 1, true, 0},
      {0x6061, 0, 1, false, 0},
      {0x6041, 0, 2, false, 0},
      {0x6007, 0, 2, true, options_.profile.abort_connection_option},  // abort connection option
  };
  if (!communication_only) {
    od_count_ = 0;
    for (const Entry& e : comm) {
      if (present(e.index)) {
        od_[od_count_++] = e;
      }
    }
    for (const Entry& e : app) {
      od_[od_count_++] = e;
    }
    return;
  }
  for (const Entry& e : comm) {
    Entry* cur = find(e.index, e.sub);
    if (cur != nullptr) {
      *cur = e;
    }
  }
}

bool EmulatedCia402Drive::present(std::uint16_t index) const noexcept {
  // TPDO n (communication 0x1800 + n - 1, mapping 0x1A00 + n - 1) exists for n <= tpdo_count.
  const unsigned count = options_.profile.tpdo_count;
  if (index >= 0x1800u && index <= 0x1803u) {
    return index - 0x1800u < count;
  }
  if (index >= 0x1A00u && index <= 0x1A03u) {
    return index - 0x1A00u < count;
  }
  return true;
}

EmulatedCia402Drive::Entry* EmulatedCia402Drive::find(std::uint16_t index, std::uint8_t sub) noexcept {
  for (std::size_t i = 0; i < od_count_; ++i) {
    if (od_[i].index == index && od_[i].sub == sub) {
      return &od_[i];
    }
  }
  return nullptr;
}

const EmulatedCia402Drive::Entry* EmulatedCia402Drive::find(std::uint16_t index,
                                                            std::uint8_t sub) const noexcept {
  for (std::size_t i = 0; i < od_count_; ++i) {
    if (od_[i].index == index && od_[i].sub == sub) {
      return &od_[i];
    }
  }
  return nullptr;
}

bool EmulatedCia402Drive::objectExists(std::uint16_t index) const noexcept {
  for (std::size_t i = 0; i < od_count_; ++i) {
    if (od_[i].index == index) {
      return true;
    }
  }
  return false;
}

std::uint32_t EmulatedCia402Drive::odValue(std::uint16_t index, std::uint8_t sub) const noexcept {
  const Entry* e = find(index, sub);
  return e != nullptr ? e->value : 0u;
}

bool EmulatedCia402Drive::od(std::uint16_t index, std::uint8_t sub, std::uint32_t* value) const noexcept {
  const Entry* e = find(index, sub);
  if (e == nullptr) {
    return false;
  }
  *value = e->value;
  return true;
}

bool EmulatedCia402Drive::pdoOk(std::uint16_t comm, std::uint16_t map, std::uint32_t cob,
                                mrqp_fw_arm_pdo which) const noexcept {
  std::uint32_t comm_cob = 0;
  if (!od(comm, 1, &comm_cob) || (comm_cob & ~kNoRtr) != cob ||
      odValue(comm, 2) != MRQP_FW_PDO_TRANSMISSION_SYNC) {
    return false;
  }
  std::uint32_t entries[4] = {0, 0, 0, 0};
  const unsigned n = mrqp_fw_arm_pdo_mapping(which, entries);
  if (odValue(map, 0) != n) {
    return false;
  }
  for (unsigned k = 0; k < n; ++k) {
    if (odValue(map, static_cast<std::uint8_t>(k + 1u)) != entries[k]) {
      return false;
    }
  }
  return true;
}

bool EmulatedCia402Drive::rpdo1Configured() const noexcept {
  return pdoOk(0x1400, 0x1600, MRQP_FW_COB_RPDO1_BASE + options_.node, MRQP_FW_ARM_RPDO1);
}
bool EmulatedCia402Drive::tpdo1Configured() const noexcept {
  return pdoOk(0x1800, 0x1A00, MRQP_FW_COB_TPDO1_BASE + options_.node, MRQP_FW_ARM_TPDO1);
}
bool EmulatedCia402Drive::tpdo2Configured() const noexcept {
  return pdoOk(0x1801, 0x1A01, MRQP_FW_COB_TPDO2_BASE + options_.node, MRQP_FW_ARM_TPDO2);
}

TimeNs EmulatedCia402Drive::syncDeadline() const noexcept {
  const std::uint32_t period_us = odValue(0x1006, 0);
  if (options_.profile.sync_timeout_factor <= 0.0 || nmt_ != MRQP_FW_NMT_STATE_OPERATIONAL ||
      last_sync_ == kNever || period_us == 0u) {
    return kNever;
  }
  return last_sync_ +
         static_cast<TimeNs>(options_.profile.sync_timeout_factor * static_cast<double>(period_us) * 1000.0);
}

TimeNs EmulatedCia402Drive::consumerDeadline() const noexcept {
  const std::uint32_t entry = odValue(0x1016, 1);
  const std::uint32_t node = (entry >> 16) & 0x7Fu;
  const std::uint32_t time_ms = entry & 0xFFFFu;
  if (!options_.profile.heartbeat_consumer || last_master_hb_ == kNever || node == 0u || time_ms == 0u) {
    return kNever;
  }
  return last_master_hb_ + ms(time_ms);
}

TimeNs EmulatedCia402Drive::rpdoDeadline() const noexcept {
  const std::uint32_t time_ms = odValue(0x1400, 5);
  if (time_ms == 0u || last_rpdo_ == kNever || nmt_ != MRQP_FW_NMT_STATE_OPERATIONAL ||
      state_ != MRQP_FW_CIA402_OPERATION_ENABLED) {
    return kNever;
  }
  return last_rpdo_ + ms(time_ms);
}

TimeNs EmulatedCia402Drive::nextEvent() const noexcept {
  TimeNs t = boot_at_ < heartbeat_due_ ? boot_at_ : heartbeat_due_;
  for (const TimeNs deadline : {syncDeadline(), consumerDeadline(), rpdoDeadline()}) {
    if (deadline != kNever && deadline + 1 < t) {
      t = deadline + 1;  // a timeout is a gap longer than the deadline
    }
  }
  return t;
}

void EmulatedCia402Drive::sendEmcy(std::uint16_t code, TimeNs at) noexcept {
  mrqp_fw_emcy e{};
  e.error_code = code;
  e.error_register = code == 0u ? 0u : MRQP_FW_ERRREG_GENERIC | MRQP_FW_ERRREG_COMMUNICATION;
  mrqp_fw_frame f;
  if (!mrqp_fw_pack_failed(mrqp_fw_emcy_pack(options_.node, &e, &f))) {
    send(f, at, false);
  }
}

void EmulatedCia402Drive::errorBehaviour() noexcept {
  // CiA 301 0x1029:01: 0 pre-operational (from Operational), 1 no change, 2 stopped.
  const std::uint32_t behaviour = odValue(0x1029, 1);
  if (behaviour == 0u && nmt_ == MRQP_FW_NMT_STATE_OPERATIONAL) {
    nmt_ = MRQP_FW_NMT_STATE_PRE_OPERATIONAL;
  } else if (behaviour == 2u) {
    nmt_ = MRQP_FW_NMT_STATE_STOPPED;
  }
  if (nmt_ != MRQP_FW_NMT_STATE_OPERATIONAL) {
    last_sync_ = kNever;
    last_rpdo_ = kNever;
  }
}

void EmulatedCia402Drive::connectionReaction(std::uint16_t code) noexcept {
  // CiA 402 0x6007 (abort connection option code), in Operation enabled: 1 fault (the fault
  // reaction completes at once: there may be no SYNC any more), 2 disable voltage (transition 9),
  // 3 quick stop (transition 11).
  if (state_ != MRQP_FW_CIA402_OPERATION_ENABLED) {
    return;
  }
  switch (odValue(0x6007, 0)) {
    case 1u:
      state_ = mrqp_fw_cia402_drive_event(state_, MRQP_FW_CIA402_EV_FAULT, nullptr);
      state_ = mrqp_fw_cia402_drive_event(state_, MRQP_FW_CIA402_EV_FAULT_REACTION_DONE, nullptr);
      error_code_ = code;
      break;
    case 2u:
      state_ = MRQP_FW_CIA402_SWITCH_ON_DISABLED;
      break;
    case 3u:
      state_ = MRQP_FW_CIA402_QUICK_STOP_ACTIVE;
      break;
    default:
      break;
  }
}

bool EmulatedCia402Drive::masterHeartbeat(const mrqp_fw_frame& f) const noexcept {
  const std::uint32_t node = (odValue(0x1016, 1) >> 16) & 0x7Fu;
  return node != 0u && f.id == MRQP_FW_COB_HEARTBEAT_BASE + node && f.len == 1u;
}

void EmulatedCia402Drive::onMasterHeartbeat(TimeNs now) noexcept {
  if (!options_.profile.heartbeat_consumer || master_hb_lost_) {
    return;
  }
  last_master_hb_ = now;
  if (hb_error_active_ && state_ != MRQP_FW_CIA402_FAULT && state_ != MRQP_FW_CIA402_FAULT_REACTION_ACTIVE) {
    hb_error_active_ = false;
    sendEmcy(0, now + options_.response_delay);  // error reset: the heartbeat is back
  }
}

void EmulatedCia402Drive::heartbeatError(TimeNs now) noexcept {
  last_master_hb_ = kNever;  // watched again from the next heartbeat heard
  hb_error_active_ = true;
  ++heartbeat_errors_;
  sendEmcy(MRQP_FW_EMCY_HEARTBEAT_ERROR, now);
  connectionReaction(MRQP_FW_EMCY_HEARTBEAT_ERROR);
  errorBehaviour();
}

void EmulatedCia402Drive::rpdoTimeout(TimeNs now) noexcept {
  last_rpdo_ = kNever;  // watched again from the next RPDO
  ++rpdo_timeouts_;
  sendEmcy(MRQP_FW_EMCY_RPDO_TIMEOUT, now);
  connectionReaction(MRQP_FW_EMCY_RPDO_TIMEOUT);
}

void EmulatedCia402Drive::commError(TimeNs now) noexcept {
  // CiA 301: EMCY 0x8100 (communication), error register generic | communication, then the
  // behaviour of 0x1029:01: 0 pre-operational (from Operational), 1 no change, 2 stopped.
  last_sync_ = kNever;
  comm_error_active_ = true;
  ++comm_errors_;
  if (options_.profile.comm_error_fault) {
    state_ = mrqp_fw_cia402_drive_event(state_, MRQP_FW_CIA402_EV_FAULT, nullptr);
    error_code_ = MRQP_FW_EMCY_COMMUNICATION;
  }
  mrqp_fw_emcy e{};
  e.error_code = MRQP_FW_EMCY_COMMUNICATION;
  e.error_register = MRQP_FW_ERRREG_GENERIC | MRQP_FW_ERRREG_COMMUNICATION;
  mrqp_fw_frame f;
  if (!mrqp_fw_pack_failed(mrqp_fw_emcy_pack(options_.node, &e, &f))) {
    send(f, now, false);
  }
  const std::uint32_t behaviour = odValue(0x1029, 1);
  if (behaviour == 0u && nmt_ == MRQP_FW_NMT_STATE_OPERATIONAL) {
    nmt_ = MRQP_FW_NMT_STATE_PRE_OPERATIONAL;
  } else if (behaviour == 2u) {
    nmt_ = MRQP_FW_NMT_STATE_STOPPED;
  }
}

std::uint16_t EmulatedCia402Drive::otherStatusBits() const noexcept {
  if (!options_.profile.statusword_bits) {
    return MRQP_FW_SW_VOLTAGE_ENABLED;
  }
  std::uint16_t bits = 0;
  switch (state_) {
    case MRQP_FW_CIA402_READY_TO_SWITCH_ON:
    case MRQP_FW_CIA402_SWITCHED_ON:
    case MRQP_FW_CIA402_OPERATION_ENABLED:
    case MRQP_FW_CIA402_QUICK_STOP_ACTIVE:
    case MRQP_FW_CIA402_FAULT_REACTION_ACTIVE:
      bits |= MRQP_FW_SW_VOLTAGE_ENABLED;
      break;
    default:
      break;
  }
  if (nmt_ == MRQP_FW_NMT_STATE_OPERATIONAL) {
    bits |= MRQP_FW_SW_REMOTE;
  }
  return bits;
}

void EmulatedCia402Drive::powerOn(TimeNs now) noexcept {
  nmt_ = MRQP_FW_NMT_STATE_BOOTUP;
  state_ = MRQP_FW_CIA402_NOT_READY_TO_SWITCH_ON;
  resetOd(false);
  heartbeat_due_ = kNever;
  boot_at_ = now + options_.boot_delay;
  last_sync_ = kNever;
  comm_error_active_ = false;
  last_master_hb_ = kNever;
  hb_error_active_ = false;
  last_rpdo_ = kNever;
  error_code_ = 0;
  controlword_ = 0;
  rpdo_pending_ = false;
}

void EmulatedCia402Drive::abortOnWrite(std::uint16_t index, std::uint8_t sub, std::uint32_t code) noexcept {
  abort_index_ = index;
  abort_sub_ = sub;
  abort_code_ = code;
}

void EmulatedCia402Drive::raiseFault(std::uint16_t code, std::uint8_t error_register, TimeNs now) noexcept {
  state_ = mrqp_fw_cia402_drive_event(state_, MRQP_FW_CIA402_EV_FAULT, nullptr);
  error_code_ = code;
  mrqp_fw_emcy e{};
  e.error_code = code;
  e.error_register = error_register;
  mrqp_fw_frame f;
  if (!mrqp_fw_pack_failed(mrqp_fw_emcy_pack(options_.node, &e, &f))) {
    send(f, now, false);
  }
}

void EmulatedCia402Drive::advance(TimeNs now) noexcept {
  const TimeNs sync = syncDeadline();
  if (sync != kNever && now > sync) {
    commError(now);
  }
  const TimeNs consumer = consumerDeadline();
  if (consumer != kNever && now > consumer) {
    heartbeatError(now);
  }
  const TimeNs rpdo = rpdoDeadline();
  if (rpdo != kNever && now > rpdo) {
    rpdoTimeout(now);
  }
  if (boot_at_ <= now) {
    // End of initialisation: boot-up message, then pre-operational.
    boot_at_ = kNever;
    mrqp_fw_frame f;
    (void)mrqp_fw_heartbeat_pack(options_.node, MRQP_FW_NMT_STATE_BOOTUP, &f);
    send(f, now, false);
    nmt_ = mrqp_fw_nmt_boot_complete(nmt_);
    state_ = mrqp_fw_cia402_drive_event(state_, MRQP_FW_CIA402_EV_INIT_COMPLETE, nullptr);
    const std::uint32_t period = odValue(0x1017, 0);
    heartbeat_due_ = period > 0u ? now + ms(period) : kNever;
  }
  if (heartbeat_due_ <= now) {
    const std::uint32_t period = odValue(0x1017, 0);
    if (period == 0u || now >= heartbeat_stop_at_) {
      heartbeat_due_ = kNever;
      return;
    }
    mrqp_fw_frame f;
    (void)mrqp_fw_heartbeat_pack(options_.node, nmt_, &f);
    send(f, now, false);
    heartbeat_due_ += ms(period);
    if (heartbeat_due_ <= now) {
      heartbeat_due_ = now + ms(period);
    }
  }
}

EmulatedCia402Drive::Received EmulatedCia402Drive::onFrame(const mrqp_fw_frame& f, TimeNs now) noexcept {
  if (f.id == MRQP_FW_COB_NMT) {
    onNmt(f, now);
    return Received::Nmt;
  }
  if (boot_at_ != kNever || nmt_ == MRQP_FW_NMT_STATE_BOOTUP) {
    return Received::Nothing;
  }
  if (masterHeartbeat(f)) {
    onMasterHeartbeat(now);
    return Received::Nothing;
  }
  if (f.id == MRQP_FW_COB_SDO_RX_BASE + options_.node &&
      (nmt_ == MRQP_FW_NMT_STATE_PRE_OPERATIONAL || nmt_ == MRQP_FW_NMT_STATE_OPERATIONAL)) {
    onSdo(f, now);
    return Received::Sdo;
  }
  if (nmt_ != MRQP_FW_NMT_STATE_OPERATIONAL) {
    return Received::Nothing;
  }
  if (f.id == MRQP_FW_COB_SYNC) {
    onSync(now);
    return Received::Sync;
  }
  if (f.id == MRQP_FW_COB_RPDO1_BASE + options_.node && rpdo1Configured()) {
    mrqp_fw_arm_rpdo1 p;
    if (mrqp_fw_arm_unpack_rpdo1(&f, options_.node, &p) == MRQP_FW_OK) {
      rpdo_controlword_ = p.controlword;
      rpdo_position_ = p.target_position;
      rpdo_torque_ = p.target_torque;
      rpdo_pending_ = true;
      last_rpdo_ = now;
      return Received::Rpdo;
    }
  }
  return Received::Nothing;
}

void EmulatedCia402Drive::onNmt(const mrqp_fw_frame& f, TimeNs now) noexcept {
  mrqp_fw_nmt_cmd cmd;
  std::uint8_t target = 0;
  if (mrqp_fw_nmt_unpack(&f, &cmd, &target) != MRQP_FW_OK || !mrqp_fw_nmt_addresses(target, options_.node)) {
    return;
  }
  const mrqp_fw_nmt_state next = mrqp_fw_nmt_next_state(nmt_, cmd);
  if (next == MRQP_FW_NMT_STATE_BOOTUP && (cmd == MRQP_FW_NMT_RESET_NODE || cmd == MRQP_FW_NMT_RESET_COMM)) {
    const bool application = cmd == MRQP_FW_NMT_RESET_NODE;
    resetOd(!application);
    if (application) {
      state_ = MRQP_FW_CIA402_NOT_READY_TO_SWITCH_ON;
      controlword_ = 0;
      rpdo_pending_ = false;
      error_code_ = 0;
    }
    nmt_ = MRQP_FW_NMT_STATE_BOOTUP;
    heartbeat_due_ = kNever;
    boot_at_ = now + options_.boot_delay;
    last_sync_ = kNever;
    comm_error_active_ = false;
    last_master_hb_ = kNever;
    hb_error_active_ = false;
    last_rpdo_ = kNever;
    host_.onNmtReset(application);
    return;
  }
  if (next != MRQP_FW_NMT_STATE_OPERATIONAL) {
    last_sync_ = kNever;  // SYNC and RPDOs are watched in Operational only
    last_rpdo_ = kNever;
  }
  nmt_ = next;
}

std::uint32_t EmulatedCia402Drive::checkWrite(const Entry& e, std::uint32_t v) const noexcept {
  const VendorProfile& p = options_.profile;
  if (!e.writable) {
    return p.abort_read_only ? MRQP_FW_SDO_ABORT_READ_ONLY : kAckIgnore;
  }
  const std::uint16_t i = e.index;
  const bool is_map = (i >= 0x1600 && i <= 0x1603) || (i >= 0x1A00 && i <= 0x1A03);
  const bool is_comm = (i >= 0x1400 && i <= 0x1403) || (i >= 0x1800 && i <= 0x1803);
  if (p.pdo_rules && is_map) {
    const std::uint16_t comm = static_cast<std::uint16_t>(i - 0x200u);
    if ((odValue(comm, 1) & kPdoInvalid) == 0u) {
      return MRQP_FW_SDO_ABORT_PARAM_INCOMPATIBLE;  // mapping changes only while the PDO is disabled
    }
    if (e.sub > 0 && odValue(i, 0) != 0u) {
      return MRQP_FW_SDO_ABORT_PARAM_INCOMPATIBLE;  // entries only while the entry count is 0
    }
    if (e.sub == 0 && v > 0u) {
      std::uint32_t bits = 0;
      for (std::uint32_t k = 1; k <= v && k <= 4u; ++k) {
        const std::uint32_t entry = odValue(i, static_cast<std::uint8_t>(k));
        const std::uint16_t obj = static_cast<std::uint16_t>(entry >> 16);
        if (entry == 0u ||
            !(obj == 0x6040 || obj == 0x6041 || obj == 0x607A || obj == 0x6064 || obj == 0x6071 ||
              obj == 0x6077 || obj == 0x606C || obj == 0x603F || obj == 0x6061)) {
          return MRQP_FW_SDO_ABORT_NOT_MAPPABLE;
        }
        bits += entry & 0xFFu;
      }
      if (v > 4u || bits > 64u) {
        return MRQP_FW_SDO_ABORT_PDO_LENGTH;
      }
    }
  }
  if (is_comm && e.sub == 1) {
    const bool now_valid = (odValue(i, 1) & kPdoInvalid) == 0u;
    const bool to_valid = (v & kPdoInvalid) == 0u;
    if (p.pdo_rules && now_valid && to_valid && v != odValue(i, 1)) {
      return MRQP_FW_SDO_ABORT_INVALID_VALUE;  // change the COB-ID only while disabled
    }
    if (p.rtr_check && i >= 0x1800u && to_valid && (v & kNoRtr) == 0u) {
      return MRQP_FW_SDO_ABORT_INVALID_VALUE;  // this drive has no RTR-capable TPDOs
    }
  }
  if (p.range_checks) {
    if (is_comm && e.sub == 2 && v >= 0xF1u && v <= 0xFBu) {
      return MRQP_FW_SDO_ABORT_INVALID_VALUE;  // reserved transmission types
    }
    if (i == 0x1006 && v != 0u && v < p.min_cycle_us) {
      return MRQP_FW_SDO_ABORT_VALUE_LOW;
    }
    if (i == 0x1017 && v != 0u && v < p.min_heartbeat_ms) {
      return MRQP_FW_SDO_ABORT_VALUE_LOW;
    }
    if (i == 0x1029 && v > 2u) {
      return MRQP_FW_SDO_ABORT_VALUE_HIGH;
    }
  }
  if (i == 0x6060 && v != static_cast<std::uint32_t>(MRQP_FW_MODE_CSP) &&
      v != static_cast<std::uint32_t>(MRQP_FW_MODE_CST)) {
    return MRQP_FW_SDO_ABORT_INVALID_VALUE;
  }
  return 0u;
}

void EmulatedCia402Drive::onSdo(const mrqp_fw_frame& f, TimeNs now) noexcept {
  const TimeNs at = now + options_.response_delay;
  mrqp_fw_sdo_msg m;
  mrqp_fw_frame out;
  if (mrqp_fw_sdo_unpack(&f, &m) != MRQP_FW_OK) {
    (void)mrqp_fw_sdo_pack_abort(options_.node, 1, 0, 0, MRQP_FW_SDO_ABORT_COMMAND, &out);
    send(out, at, false);
    return;
  }
  std::uint32_t abort = 0;
  Entry* e = find(m.index, m.subindex);
  if (m.kind == MRQP_FW_SDO_DOWNLOAD_INIT_REQ) {
    ++sdo_writes_;
    std::uint32_t v = 0;
    for (unsigned k = 0; k < m.n && k < 4u; ++k) {
      v |= static_cast<std::uint32_t>(m.data[k]) << (8u * k);
    }
    if (!m.expedited) {
      abort = MRQP_FW_SDO_ABORT_COMMAND;  // segmented writes are not needed by this drive
    } else if (e == nullptr) {
      abort = !options_.profile.abort_absent ? kAckIgnore
              : objectExists(m.index)        ? MRQP_FW_SDO_ABORT_NO_SUBINDEX
                                             : MRQP_FW_SDO_ABORT_NO_OBJECT;
    } else if (m.n != e->size) {
      abort = MRQP_FW_SDO_ABORT_TYPE_LENGTH;
    } else if (abort_code_ != 0u && m.index == abort_index_ && m.subindex == abort_sub_) {
      abort = abort_code_;
    } else {
      abort = checkWrite(*e, v);
    }
    if (abort == kAckIgnore) {
      abort = 0;
      (void)mrqp_fw_sdo_pack_download_resp(options_.node, m.index, m.subindex, &out);
    } else if (abort == 0u) {
      e->value = v;
      if (m.index == 0x6060) {
        find(0x6061, 0)->value = v;  // mode display follows
      }
      if (m.index == 0x6040) {
        // A controlword by SDO (e.g. a master stopping a drive whose PDOs are off) acts at once.
        state_ = mrqp_fw_cia402_drive_next(state_, static_cast<std::uint16_t>(v), controlword_, nullptr);
        controlword_ = static_cast<std::uint16_t>(v);
      }
      if (m.index == 0x1017) {
        heartbeat_due_ = v > 0u ? now + ms(v) : kNever;
      }
      (void)mrqp_fw_sdo_pack_download_resp(options_.node, m.index, m.subindex, &out);
    }
  } else if (m.kind == MRQP_FW_SDO_UPLOAD_INIT_REQ) {
    if (e == nullptr) {
      abort = objectExists(m.index) ? MRQP_FW_SDO_ABORT_NO_SUBINDEX : MRQP_FW_SDO_ABORT_NO_OBJECT;
    } else {
      std::uint8_t d[4];
      for (unsigned k = 0; k < 4u; ++k) {
        d[k] = static_cast<std::uint8_t>((e->value >> (8u * k)) & 0xFFu);
      }
      (void)mrqp_fw_sdo_pack_upload_resp(options_.node, m.index, m.subindex, d, e->size, &out);
    }
  } else {
    abort = MRQP_FW_SDO_ABORT_COMMAND;
  }
  if (abort != 0u) {
    (void)mrqp_fw_sdo_pack_abort(options_.node, 1, m.index, m.subindex, abort, &out);
  }
  send(out, at, false);
}

void EmulatedCia402Drive::onSync(TimeNs now) noexcept {
  const TimeNs at = now + options_.response_delay;
  ++syncs_;
  last_sync_ = now;
  // Fault reaction completes at the next SYNC.
  state_ = mrqp_fw_cia402_drive_event(state_, MRQP_FW_CIA402_EV_FAULT_REACTION_DONE, nullptr);
  const bool new_targets = rpdo_pending_;
  if (rpdo_pending_) {
    rpdo_pending_ = false;
    const mrqp_fw_cia402_state before = state_;
    state_ = mrqp_fw_cia402_drive_next(state_, rpdo_controlword_, controlword_, nullptr);
    controlword_ = rpdo_controlword_;
    target_position_ = rpdo_position_;
    target_torque_ = rpdo_torque_;
    if (before == MRQP_FW_CIA402_FAULT && state_ != MRQP_FW_CIA402_FAULT) {
      error_code_ = 0;
      comm_error_active_ = false;
      hb_error_active_ = false;
      mrqp_fw_emcy e{};
      mrqp_fw_frame f;
      (void)mrqp_fw_emcy_pack(options_.node, &e, &f);  // error reset
      send(f, at, false);
    }
  }
  if (comm_error_active_ && state_ != MRQP_FW_CIA402_FAULT &&
      state_ != MRQP_FW_CIA402_FAULT_REACTION_ACTIVE) {
    // SYNC is back and the power stage never faulted: the communication error is over.
    comm_error_active_ = false;
    mrqp_fw_emcy e{};
    mrqp_fw_frame f;
    (void)mrqp_fw_emcy_pack(options_.node, &e, &f);  // error reset
    send(f, at, false);
  }
  const Feedback fb = host_.onSync(*this, new_targets, now);
  if (pdo_silent_) {
    return;
  }
  mrqp_fw_frame f;
  if (tpdo1Configured()) {
    const mrqp_fw_arm_tpdo1 t{mrqp_fw_cia402_statusword(state_, otherStatusBits()), fb.position, fb.torque};
    (void)mrqp_fw_arm_pack_tpdo1(options_.node, &t, &f);
    send(f, at, true);
  }
  if (tpdo2Configured()) {
    const mrqp_fw_arm_tpdo2 t{fb.velocity, error_code_, force_mode_ ? forced_mode_ : mode()};
    (void)mrqp_fw_arm_pack_tpdo2(options_.node, &t, &f);
    send(f, at, true);
  }
}

}  // namespace mrqp::emulation
