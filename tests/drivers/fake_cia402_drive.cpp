// A fake CiA 402 drive (see fake_cia402_drive.hpp).
#include "fake_cia402_drive.hpp"

namespace drvtest {

using mrqp::drivers::ReceiveResult;

namespace {
constexpr std::uint32_t kPdoInvalid = 0x80000000u;
}

FakeCia402Drive::FakeCia402Drive(SimNode& node, const FakeDriveOptions& options) : node_(node), opt_(options)
{
  position_ = options.initial_position;
  reset_od(false);
  node_.set_listener(this);
  // Power-on: initialisation, then the boot-up message.
  booting_ = true;
  node_.set_timer(opt_.boot_delay);
}

void FakeCia402Drive::reset_od(bool communication_only) noexcept
{
  const std::uint32_t n = opt_.node;
  const Entry comm[] = {
      {0x1000, 0, 4, false, 0x00020192u},          // device type: CiA 402 drive
      {0x1006, 0, 4, true, 0},                     // communication cycle period
      {0x1016, 0, 1, false, 1},                    // consumer heartbeat: one entry
      {0x1016, 1, 4, true, 0},
      {0x1017, 0, 2, true, 0},                     // producer heartbeat time
      {0x1400, 1, 4, true, 0x200u + n},            // RPDO1: valid by default...
      {0x1400, 2, 1, true, 0xFF},
      {0x1600, 0, 1, true, 1},                     // ... mapping only the controlword
      {0x1600, 1, 4, true, 0x60400010u},
      {0x1600, 2, 4, true, 0},
      {0x1600, 3, 4, true, 0},
      {0x1600, 4, 4, true, 0},
      {0x1800, 1, 4, true, 0x180u + n},            // TPDO1: valid, asynchronous, statusword only
      {0x1800, 2, 1, true, 0xFF},
      {0x1801, 1, 4, true, kPdoInvalid | (0x280u + n)},
      {0x1801, 2, 1, true, 0xFF},
      {0x1802, 1, 4, true, 0x380u + n},            // TPDO3/4 valid by default: must be disabled
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
  };
  const Entry app[] = {
      {0x6060, 0, 1, true, 0},
      {0x6061, 0, 1, false, 0},
      {0x6041, 0, 2, false, 0},
  };
  if (!communication_only) {
    od_count_ = 0;
    for (const Entry& e : comm) {
      od_[od_count_++] = e;
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

FakeCia402Drive::Entry* FakeCia402Drive::find(std::uint16_t index, std::uint8_t sub) noexcept
{
  for (std::size_t i = 0; i < od_count_; ++i) {
    if (od_[i].index == index && od_[i].sub == sub) {
      return &od_[i];
    }
  }
  return nullptr;
}

const FakeCia402Drive::Entry* FakeCia402Drive::find(std::uint16_t index, std::uint8_t sub) const noexcept
{
  for (std::size_t i = 0; i < od_count_; ++i) {
    if (od_[i].index == index && od_[i].sub == sub) {
      return &od_[i];
    }
  }
  return nullptr;
}

bool FakeCia402Drive::object_exists(std::uint16_t index) const noexcept
{
  for (std::size_t i = 0; i < od_count_; ++i) {
    if (od_[i].index == index) {
      return true;
    }
  }
  return false;
}

std::uint32_t FakeCia402Drive::value(std::uint16_t index, std::uint8_t sub) const noexcept
{
  const Entry* e = find(index, sub);
  return e != nullptr ? e->value : 0u;
}

bool FakeCia402Drive::od(std::uint16_t index, std::uint8_t sub, std::uint32_t* v) const noexcept
{
  const Entry* e = find(index, sub);
  if (e == nullptr) {
    return false;
  }
  *v = e->value;
  return true;
}

bool FakeCia402Drive::pdo_ok(std::uint16_t comm, std::uint16_t map, std::uint32_t cob, mrqp_fw_arm_pdo which) const noexcept
{
  if (value(comm, 1) != cob || value(comm, 2) != MRQP_FW_PDO_TRANSMISSION_SYNC) {
    return false;
  }
  std::uint32_t entries[4] = {0, 0, 0, 0};
  const unsigned n = mrqp_fw_arm_pdo_mapping(which, entries);
  if (value(map, 0) != n) {
    return false;
  }
  for (unsigned k = 0; k < n; ++k) {
    if (value(map, static_cast<std::uint8_t>(k + 1)) != entries[k]) {
      return false;
    }
  }
  return true;
}

bool FakeCia402Drive::rpdo1_configured() const noexcept
{
  return pdo_ok(0x1400, 0x1600, 0x200u + opt_.node, MRQP_FW_ARM_RPDO1);
}
bool FakeCia402Drive::tpdo1_configured() const noexcept
{
  return pdo_ok(0x1800, 0x1A00, 0x180u + opt_.node, MRQP_FW_ARM_TPDO1);
}
bool FakeCia402Drive::tpdo2_configured() const noexcept
{
  return pdo_ok(0x1801, 0x1A01, 0x280u + opt_.node, MRQP_FW_ARM_TPDO2);
}

void FakeCia402Drive::send_later(const mrqp_fw_frame& f, TimeNs at) noexcept
{
  (void)node_.send_at(f, at);
}

void FakeCia402Drive::power(bool on) noexcept
{
  powered_ = on;
  node_.set_connected(on);
  if (on) {
    nmt_ = MRQP_FW_NMT_STATE_BOOTUP;
    state_ = MRQP_FW_CIA402_NOT_READY_TO_SWITCH_ON;
    reset_od(false);
    booting_ = true;
    node_.set_timer(node_.bus().now() + opt_.boot_delay);
  }
}

void FakeCia402Drive::abort_on_write(std::uint16_t index, std::uint8_t sub, std::uint32_t code) noexcept
{
  abort_index_ = index;
  abort_sub_ = sub;
  abort_code_ = code;
}

void FakeCia402Drive::inject_fault(std::uint16_t code, std::uint8_t error_register) noexcept
{
  state_ = mrqp_fw_cia402_drive_event(state_, MRQP_FW_CIA402_EV_FAULT, nullptr);
  error_code_ = code;
  mrqp_fw_emcy e{};
  e.error_code = code;
  e.error_register = error_register;
  mrqp_fw_frame f;
  if (!mrqp_fw_pack_failed(mrqp_fw_emcy_pack(opt_.node, &e, &f))) {
    (void)node_.send(f);
  }
}

void FakeCia402Drive::on_timer(SimNode&, TimeNs now) noexcept
{
  if (booting_) {
    // End of initialisation: boot-up message, then pre-operational.
    booting_ = false;
    mrqp_fw_frame f;
    (void)mrqp_fw_heartbeat_pack(opt_.node, MRQP_FW_NMT_STATE_BOOTUP, &f);
    (void)node_.send(f);
    nmt_ = mrqp_fw_nmt_boot_complete(nmt_);
    state_ = mrqp_fw_cia402_drive_event(state_, MRQP_FW_CIA402_EV_INIT_COMPLETE, nullptr);
    const std::uint32_t period = value(0x1017, 0);
    if (period > 0u) {
      heartbeat_due_ = now + static_cast<TimeNs>(period) * 1000000;
      node_.set_timer(heartbeat_due_);
    }
    return;
  }
  const std::uint32_t period = value(0x1017, 0);
  if (period == 0u || nmt_ == MRQP_FW_NMT_STATE_BOOTUP) {
    return;
  }
  mrqp_fw_frame f;
  (void)mrqp_fw_heartbeat_pack(opt_.node, nmt_, &f);
  (void)node_.send(f);
  heartbeat_due_ += static_cast<TimeNs>(period) * 1000000;
  if (heartbeat_due_ <= now) {
    heartbeat_due_ = now + static_cast<TimeNs>(period) * 1000000;
  }
  node_.set_timer(heartbeat_due_);
}

void FakeCia402Drive::on_transmitted(SimNode&, const mrqp_fw_frame&, TimeNs) noexcept {}

void FakeCia402Drive::on_receive(SimNode&, ReceiveResult kind, const RxFrame& rx) noexcept
{
  if (kind != ReceiveResult::Frame || !powered_) {
    return;
  }
  const mrqp_fw_frame& f = rx.frame;
  const TimeNs now = rx.timestamp;
  if (f.id == MRQP_FW_COB_NMT) {
    on_nmt(f, now);
    return;
  }
  if (booting_ || nmt_ == MRQP_FW_NMT_STATE_BOOTUP) {
    return;
  }
  if (f.id == MRQP_FW_COB_SDO_RX_BASE + opt_.node &&
      (nmt_ == MRQP_FW_NMT_STATE_PRE_OPERATIONAL || nmt_ == MRQP_FW_NMT_STATE_OPERATIONAL)) {
    on_sdo(f, now);
    return;
  }
  if (nmt_ != MRQP_FW_NMT_STATE_OPERATIONAL) {
    return;
  }
  if (f.id == MRQP_FW_COB_SYNC) {
    on_sync(now);
    return;
  }
  if (f.id == MRQP_FW_COB_RPDO1_BASE + opt_.node && rpdo1_configured()) {
    mrqp_fw_arm_rpdo1 p;
    if (mrqp_fw_arm_unpack_rpdo1(&f, opt_.node, &p) == MRQP_FW_OK) {
      rpdo_controlword_ = p.controlword;
      rpdo_position_ = p.target_position;
      rpdo_torque_ = p.target_torque;
      rpdo_pending_ = true;
    }
  }
}

void FakeCia402Drive::on_nmt(const mrqp_fw_frame& f, TimeNs now) noexcept
{
  mrqp_fw_nmt_cmd cmd;
  std::uint8_t target = 0;
  if (mrqp_fw_nmt_unpack(&f, &cmd, &target) != MRQP_FW_OK || !mrqp_fw_nmt_addresses(target, opt_.node)) {
    return;
  }
  const mrqp_fw_nmt_state next = mrqp_fw_nmt_next_state(nmt_, cmd);
  if (next == MRQP_FW_NMT_STATE_BOOTUP && (cmd == MRQP_FW_NMT_RESET_NODE || cmd == MRQP_FW_NMT_RESET_COMM)) {
    node_.cancel_pending();
    reset_od(cmd == MRQP_FW_NMT_RESET_COMM);
    if (cmd == MRQP_FW_NMT_RESET_NODE) {
      state_ = MRQP_FW_CIA402_NOT_READY_TO_SWITCH_ON;
      controlword_ = 0;
      rpdo_pending_ = false;
    }
    nmt_ = MRQP_FW_NMT_STATE_BOOTUP;
    booting_ = true;
    node_.set_timer(now + opt_.boot_delay);
    return;
  }
  nmt_ = next;
}

std::uint32_t FakeCia402Drive::check_write(const Entry& e, std::uint32_t v) const noexcept
{
  if (!e.writable) {
    return MRQP_FW_SDO_ABORT_READ_ONLY;
  }
  const std::uint16_t i = e.index;
  const bool is_map = (i >= 0x1600 && i <= 0x1603) || (i >= 0x1A00 && i <= 0x1A03);
  const bool is_comm = (i >= 0x1400 && i <= 0x1403) || (i >= 0x1800 && i <= 0x1803);
  if (is_map) {
    const std::uint16_t comm = static_cast<std::uint16_t>(i - 0x200u);
    const bool pdo_disabled = (value(comm, 1) & kPdoInvalid) != 0u;
    if (!pdo_disabled) {
      return MRQP_FW_SDO_ABORT_PARAM_INCOMPATIBLE;  // mapping changes only while the PDO is disabled
    }
    if (e.sub > 0 && value(i, 0) != 0u) {
      return MRQP_FW_SDO_ABORT_PARAM_INCOMPATIBLE;  // entries only while the entry count is 0
    }
    if (e.sub == 0 && v > 0u) {
      std::uint32_t bits = 0;
      for (std::uint32_t k = 1; k <= v; ++k) {
        const std::uint32_t entry = value(i, static_cast<std::uint8_t>(k));
        const std::uint16_t obj = static_cast<std::uint16_t>(entry >> 16);
        if (entry == 0u || !(obj == 0x6040 || obj == 0x6041 || obj == 0x607A || obj == 0x6064 || obj == 0x6071 ||
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
    const bool now_valid = (value(i, 1) & kPdoInvalid) == 0u;
    const bool to_valid = (v & kPdoInvalid) == 0u;
    if (now_valid && to_valid && v != value(i, 1)) {
      return MRQP_FW_SDO_ABORT_INVALID_VALUE;  // change the COB-ID only while disabled
    }
  }
  if (i == 0x6060 && v != static_cast<std::uint32_t>(MRQP_FW_MODE_CSP) &&
      v != static_cast<std::uint32_t>(MRQP_FW_MODE_CST)) {
    return MRQP_FW_SDO_ABORT_INVALID_VALUE;
  }
  return 0u;
}

void FakeCia402Drive::on_sdo(const mrqp_fw_frame& f, TimeNs now) noexcept
{
  mrqp_fw_sdo_msg m;
  mrqp_fw_frame out;
  if (mrqp_fw_sdo_unpack(&f, &m) != MRQP_FW_OK) {
    (void)mrqp_fw_sdo_pack_abort(opt_.node, 1, 0, 0, MRQP_FW_SDO_ABORT_COMMAND, &out);
    send_later(out, now + opt_.response_delay);
    return;
  }
  std::uint32_t abort = 0;
  Entry* e = find(m.index, m.subindex);
  if (m.kind == MRQP_FW_SDO_DOWNLOAD_INIT_REQ) {
    ++sdo_writes_;
    std::uint32_t v = 0;
    for (unsigned k = 0; k < m.n && k < 4; ++k) {
      v |= static_cast<std::uint32_t>(m.data[k]) << (8 * k);
    }
    if (!m.expedited) {
      abort = MRQP_FW_SDO_ABORT_COMMAND;  // segmented writes are not needed by this drive
    } else if (e == nullptr) {
      abort = object_exists(m.index) ? MRQP_FW_SDO_ABORT_NO_SUBINDEX : MRQP_FW_SDO_ABORT_NO_OBJECT;
    } else if (m.n != e->size) {
      abort = MRQP_FW_SDO_ABORT_TYPE_LENGTH;
    } else if (abort_code_ != 0u && m.index == abort_index_ && m.subindex == abort_sub_) {
      abort = abort_code_;
    } else {
      abort = check_write(*e, v);
    }
    if (abort == 0u) {
      e->value = v;
      if (m.index == 0x6060) {
        Entry* d = find(0x6061, 0);
        d->value = v;
      }
      if (m.index == 0x1017 && v > 0u) {
        heartbeat_due_ = now + static_cast<TimeNs>(v) * 1000000;
        node_.set_timer(heartbeat_due_);
      }
      (void)mrqp_fw_sdo_pack_download_resp(opt_.node, m.index, m.subindex, &out);
    }
  } else if (m.kind == MRQP_FW_SDO_UPLOAD_INIT_REQ) {
    if (e == nullptr) {
      abort = object_exists(m.index) ? MRQP_FW_SDO_ABORT_NO_SUBINDEX : MRQP_FW_SDO_ABORT_NO_OBJECT;
    } else {
      std::uint8_t d[4];
      for (unsigned k = 0; k < 4; ++k) {
        d[k] = static_cast<std::uint8_t>((e->value >> (8 * k)) & 0xFFu);
      }
      (void)mrqp_fw_sdo_pack_upload_resp(opt_.node, m.index, m.subindex, d, e->size, &out);
    }
  } else {
    abort = MRQP_FW_SDO_ABORT_COMMAND;
  }
  if (abort != 0u) {
    (void)mrqp_fw_sdo_pack_abort(opt_.node, 1, m.index, m.subindex, abort, &out);
  }
  send_later(out, now + opt_.response_delay);
}

void FakeCia402Drive::on_sync(TimeNs now) noexcept
{
  ++syncs_;
  // Fault reaction completes at the next SYNC.
  state_ = mrqp_fw_cia402_drive_event(state_, MRQP_FW_CIA402_EV_FAULT_REACTION_DONE, nullptr);
  if (rpdo_pending_) {
    rpdo_pending_ = false;
    const mrqp_fw_cia402_state before = state_;
    state_ = mrqp_fw_cia402_drive_next(state_, rpdo_controlword_, controlword_, nullptr);
    controlword_ = rpdo_controlword_;
    target_position_ = rpdo_position_;
    target_torque_ = rpdo_torque_;
    if (before == MRQP_FW_CIA402_FAULT && state_ != MRQP_FW_CIA402_FAULT) {
      error_code_ = 0;
      mrqp_fw_emcy e{};
      mrqp_fw_frame f;
      (void)mrqp_fw_emcy_pack(opt_.node, &e, &f);  // error reset
      send_later(f, now + opt_.response_delay);
    }
  }
  const std::int8_t mode = static_cast<std::int8_t>(value(0x6060, 0));
  const std::int32_t before = position_;
  if (state_ == MRQP_FW_CIA402_OPERATION_ENABLED) {
    if (mode == MRQP_FW_MODE_CSP) {
      position_ = target_position_;
      torque_ = 0;
    } else {
      torque_ = target_torque_;
    }
  } else {
    torque_ = 0;
  }
  const std::uint32_t period_us = value(0x1006, 0);
  velocity_ = period_us > 0u ? static_cast<std::int32_t>(static_cast<std::int64_t>(position_ - before) * 1000000 /
                                                         static_cast<std::int64_t>(period_us))
                             : 0;
  if (pdo_silent_) {
    return;
  }
  mrqp_fw_frame f;
  if (tpdo1_configured()) {
    mrqp_fw_arm_tpdo1 t{mrqp_fw_cia402_statusword(state_, MRQP_FW_SW_VOLTAGE_ENABLED), position_, torque_};
    (void)mrqp_fw_arm_pack_tpdo1(opt_.node, &t, &f);
    send_later(f, now + opt_.response_delay);
  }
  if (tpdo2_configured()) {
    mrqp_fw_arm_tpdo2 t{velocity_, error_code_, force_mode_ ? forced_mode_ : mode};
    (void)mrqp_fw_arm_pack_tpdo2(opt_.node, &t, &f);
    send_later(f, now + opt_.response_delay);
  }
}

}  // namespace drvtest
