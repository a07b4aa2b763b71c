// The drive side of the CiA 402 arm protocol (see drive_emu.hpp). Object dictionary rules as in
// CiA 301: PDO mapping only while the PDO is disabled and its entry count is 0.
#include "drive_emu.hpp"

#include <algorithm>
#include <cmath>

namespace mrqp::drive_emu {

namespace {
constexpr std::uint32_t kPdoInvalid = 0x80000000u;

struct Entry {
  std::uint16_t index;
  std::uint8_t sub;
  std::uint8_t size;
  bool writable;
  std::uint32_t value;
};
}  // namespace

struct DriveEmulator::Drive {
  EmuNode cfg;
  std::array<Entry, 48> od{};
  std::size_t od_count = 0;
  mrqp_fw_nmt_state nmt = MRQP_FW_NMT_STATE_BOOTUP;
  mrqp_fw_cia402_state state = MRQP_FW_CIA402_NOT_READY_TO_SWITCH_ON;
  TimeNs boot_at = 0;            ///< kNever: not booting
  TimeNs heartbeat_due = kNever;
  bool emcy_done = false;
  std::uint16_t controlword = 0;
  std::uint16_t rpdo_controlword = 0;
  std::int32_t rpdo_position = 0;
  std::int16_t rpdo_torque = 0;
  bool rpdo_pending = false;
  double target_position = 0.0;  ///< rad
  double target_torque = 0.0;    ///< N m
  double q = 0.0;
  double qd = 0.0;
  double tau = 0.0;
  std::uint16_t error_code = 0;
  TimeNs now = 0;

  Entry* find(std::uint16_t index, std::uint8_t sub) noexcept
  {
    for (std::size_t i = 0; i < od_count; ++i) {
      if (od[i].index == index && od[i].sub == sub) {
        return &od[i];
      }
    }
    return nullptr;
  }
  bool exists(std::uint16_t index) const noexcept
  {
    for (std::size_t i = 0; i < od_count; ++i) {
      if (od[i].index == index) {
        return true;
      }
    }
    return false;
  }
  std::uint32_t value(std::uint16_t index, std::uint8_t sub) noexcept
  {
    const Entry* e = find(index, sub);
    return e != nullptr ? e->value : 0u;
  }
  void reset_od(bool communication_only) noexcept
  {
    const std::uint32_t n = cfg.node;
    const Entry comm[] = {
        {0x1000, 0, 4, false, 0x00020192u}, {0x1006, 0, 4, true, 0},
        {0x1016, 0, 1, false, 1},           {0x1016, 1, 4, true, 0},
        {0x1017, 0, 2, true, 0},            {0x1400, 1, 4, true, 0x200u + n},
        {0x1400, 2, 1, true, 0xFF},         {0x1600, 0, 1, true, 1},
        {0x1600, 1, 4, true, 0x60400010u},  {0x1600, 2, 4, true, 0},
        {0x1600, 3, 4, true, 0},            {0x1600, 4, 4, true, 0},
        {0x1800, 1, 4, true, 0x180u + n},   {0x1800, 2, 1, true, 0xFF},
        {0x1801, 1, 4, true, kPdoInvalid | (0x280u + n)},
        {0x1801, 2, 1, true, 0xFF},         {0x1802, 1, 4, true, 0x380u + n},
        {0x1802, 2, 1, true, 0xFF},         {0x1803, 1, 4, true, 0x480u + n},
        {0x1803, 2, 1, true, 0xFF},         {0x1A00, 0, 1, true, 1},
        {0x1A00, 1, 4, true, 0x60410010u},  {0x1A00, 2, 4, true, 0},
        {0x1A00, 3, 4, true, 0},            {0x1A00, 4, 4, true, 0},
        {0x1A01, 0, 1, true, 0},            {0x1A01, 1, 4, true, 0},
        {0x1A01, 2, 4, true, 0},            {0x1A01, 3, 4, true, 0},
        {0x1A01, 4, 4, true, 0},
    };
    const Entry app[] = {{0x6060, 0, 1, true, 0}, {0x6061, 0, 1, false, 0}, {0x6041, 0, 2, false, 0}};
    if (!communication_only) {
      od_count = 0;
      for (const Entry& e : comm) {
        od[od_count++] = e;
      }
      for (const Entry& e : app) {
        od[od_count++] = e;
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
  bool pdo_ok(std::uint16_t comm, std::uint16_t map, std::uint32_t cob, mrqp_fw_arm_pdo which) noexcept
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
  bool rpdo1_ok() noexcept { return pdo_ok(0x1400, 0x1600, 0x200u + cfg.node, MRQP_FW_ARM_RPDO1); }
  bool tpdo1_ok() noexcept { return pdo_ok(0x1800, 0x1A00, 0x180u + cfg.node, MRQP_FW_ARM_TPDO1); }
  bool tpdo2_ok() noexcept { return pdo_ok(0x1801, 0x1A01, 0x280u + cfg.node, MRQP_FW_ARM_TPDO2); }

  std::uint32_t check_write(const Entry& e, std::uint32_t v) noexcept
  {
    if (!e.writable) {
      return MRQP_FW_SDO_ABORT_READ_ONLY;
    }
    const std::uint16_t i = e.index;
    const bool is_map = (i >= 0x1600 && i <= 0x1603) || (i >= 0x1A00 && i <= 0x1A03);
    const bool is_comm = (i >= 0x1400 && i <= 0x1403) || (i >= 0x1800 && i <= 0x1803);
    if (is_map) {
      const std::uint16_t comm = static_cast<std::uint16_t>(i - 0x200u);
      if ((value(comm, 1) & kPdoInvalid) == 0u) {
        return MRQP_FW_SDO_ABORT_PARAM_INCOMPATIBLE;
      }
      if (e.sub > 0 && value(i, 0) != 0u) {
        return MRQP_FW_SDO_ABORT_PARAM_INCOMPATIBLE;
      }
      if (e.sub == 0 && v > 0u) {
        std::uint32_t bits = 0;
        for (std::uint32_t k = 1; k <= v && k <= 4; ++k) {
          const std::uint32_t entry = value(i, static_cast<std::uint8_t>(k));
          const std::uint16_t obj = static_cast<std::uint16_t>(entry >> 16);
          if (entry == 0u || !(obj == 0x6040 || obj == 0x6041 || obj == 0x607A || obj == 0x6064 ||
                               obj == 0x6071 || obj == 0x6077 || obj == 0x606C || obj == 0x603F ||
                               obj == 0x6061)) {
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
        return MRQP_FW_SDO_ABORT_INVALID_VALUE;
      }
    }
    if (i == 0x6060 && v != static_cast<std::uint32_t>(MRQP_FW_MODE_CSP) &&
        v != static_cast<std::uint32_t>(MRQP_FW_MODE_CST)) {
      return MRQP_FW_SDO_ABORT_INVALID_VALUE;
    }
    return 0u;
  }
};

DriveEmulator::DriveEmulator(const EmuConfig& config, FrameSink& sink) : cfg_(config), sink_(sink)
{
  rng_ = 0x9E3779B97F4A7C15ull ^ config.seed;
  drives_.resize(config.nodes.size());
  for (std::size_t i = 0; i < drives_.size(); ++i) {
    Drive& d = drives_[i];
    d.cfg = config.nodes[i];
    d.reset_od(false);
    d.q = d.cfg.joint.initial_position;
    d.target_position = d.q;
    d.boot_at = config.boot_delay;  // power-on
  }
}

double DriveEmulator::rand01() noexcept
{
  rng_ ^= rng_ << 13;
  rng_ ^= rng_ >> 7;
  rng_ ^= rng_ << 17;
  return static_cast<double>(rng_ >> 11) * (1.0 / 9007199254740992.0);
}

void DriveEmulator::send(const mrqp_fw_frame& f, TimeNs now) noexcept
{
  if (cfg_.drop_fraction > 0.0 && rand01() < cfg_.drop_fraction) {
    ++stats_.dropped;
    return;
  }
  if (cfg_.corrupt_fraction > 0.0 && rand01() < cfg_.corrupt_fraction) {
    mrqp_fw_frame c = f;
    c.len = 1;  // truncated: fails to decode at the master
    ++stats_.corrupted;
    ++stats_.sent;
    sink_.emit(c, now);
    return;
  }
  ++stats_.sent;
  sink_.emit(f, now);
}

DriveEmulator::~DriveEmulator() = default;
std::size_t DriveEmulator::size() const noexcept { return drives_.size(); }
double DriveEmulator::position(std::size_t i) const noexcept { return drives_[i].q; }
mrqp_fw_cia402_state DriveEmulator::state(std::size_t i) const noexcept { return drives_[i].state; }
mrqp_fw_nmt_state DriveEmulator::nmt(std::size_t i) const noexcept { return drives_[i].nmt; }

TimeNs DriveEmulator::next_event() const noexcept
{
  TimeNs t = next_step_;
  for (const Drive& d : drives_) {
    t = std::min(t, d.boot_at);
    t = std::min(t, d.heartbeat_due);
    if (!d.emcy_done) {
      t = std::min(t, d.cfg.faults.emcy_at);
    }
  }
  return t;
}

void DriveEmulator::step(Drive& d, double dt) noexcept
{
  const JointModel& j = d.cfg.joint;
  double tau = 0.0;
  if (d.state == MRQP_FW_CIA402_OPERATION_ENABLED) {
    const std::int8_t mode = static_cast<std::int8_t>(d.value(0x6060, 0));
    if (mode == MRQP_FW_MODE_CSP) {
      tau = j.kp * (d.target_position - d.q) - j.kd * d.qd;
    } else {
      tau = d.target_torque;
    }
  }
  tau = std::clamp(tau, -j.torque_limit, j.torque_limit);
  if (d.now >= d.cfg.faults.saturate_at) {
    tau = j.torque_limit;
  }
  d.tau = tau;
  const double qdd = (tau - j.damping * d.qd) / j.inertia;
  d.qd += qdd * dt;  // semi-implicit Euler
  d.q += d.qd * dt;
}

void DriveEmulator::advance(TimeNs now) noexcept
{
  while (next_event() <= now) {
    const TimeNs t = next_event();
    for (Drive& d : drives_) {
      d.now = t;
      if (d.boot_at <= t) {
        // End of initialisation: boot-up message, then pre-operational.
        d.boot_at = kNever;
        mrqp_fw_frame f;
        (void)mrqp_fw_heartbeat_pack(d.cfg.node, MRQP_FW_NMT_STATE_BOOTUP, &f);
        send(f, t);
        d.nmt = mrqp_fw_nmt_boot_complete(d.nmt);
        d.state = mrqp_fw_cia402_drive_event(d.state, MRQP_FW_CIA402_EV_INIT_COMPLETE, nullptr);
        const std::uint32_t period = d.value(0x1017, 0);
        d.heartbeat_due = period > 0u ? t + static_cast<TimeNs>(period) * 1000000 : kNever;
      }
      if (d.heartbeat_due <= t) {
        const std::uint32_t period = d.value(0x1017, 0);
        if (period == 0u || t >= d.cfg.faults.heartbeat_stop_at) {
          d.heartbeat_due = kNever;
        } else {
          mrqp_fw_frame f;
          (void)mrqp_fw_heartbeat_pack(d.cfg.node, d.nmt, &f);
          send(f, t);
          d.heartbeat_due += static_cast<TimeNs>(period) * 1000000;
          if (d.heartbeat_due <= t) {
            d.heartbeat_due = t + static_cast<TimeNs>(period) * 1000000;
          }
        }
      }
      if (!d.emcy_done && d.cfg.faults.emcy_at <= t) {
        d.emcy_done = true;
        d.state = mrqp_fw_cia402_drive_event(d.state, MRQP_FW_CIA402_EV_FAULT, nullptr);
        d.error_code = d.cfg.faults.emcy_code;
        mrqp_fw_emcy e{};
        e.error_code = d.cfg.faults.emcy_code;
        e.error_register = 0x03;
        mrqp_fw_frame f;
        if (!mrqp_fw_pack_failed(mrqp_fw_emcy_pack(d.cfg.node, &e, &f))) {
          send(f, t);
        }
      }
    }
    if (next_step_ <= t) {
      const double dt = static_cast<double>(cfg_.step) * 1e-9;
      for (Drive& d : drives_) {
        step(d, dt);
      }
      next_step_ += cfg_.step;
    }
  }
}

void DriveEmulator::on_frame(const mrqp_fw_frame& f, TimeNs now) noexcept
{
  for (Drive& d : drives_) {
    d.now = now;
    if (f.id == MRQP_FW_COB_NMT) {
      on_nmt(d, f, now);
      continue;
    }
    if (d.boot_at != kNever || d.nmt == MRQP_FW_NMT_STATE_BOOTUP) {
      continue;
    }
    if (f.id == MRQP_FW_COB_SDO_RX_BASE + d.cfg.node &&
        (d.nmt == MRQP_FW_NMT_STATE_PRE_OPERATIONAL || d.nmt == MRQP_FW_NMT_STATE_OPERATIONAL)) {
      on_sdo(d, f, now);
      continue;
    }
    if (d.nmt != MRQP_FW_NMT_STATE_OPERATIONAL) {
      continue;
    }
    if (f.id == MRQP_FW_COB_SYNC) {
      on_sync(d, now);
      continue;
    }
    if (f.id == MRQP_FW_COB_RPDO1_BASE + d.cfg.node && d.rpdo1_ok()) {
      mrqp_fw_arm_rpdo1 p;
      if (mrqp_fw_arm_unpack_rpdo1(&f, d.cfg.node, &p) == MRQP_FW_OK) {
        d.rpdo_controlword = p.controlword;
        d.rpdo_position = p.target_position;
        d.rpdo_torque = p.target_torque;
        d.rpdo_pending = true;
        ++stats_.rpdos;
      }
    }
  }
  if (f.id == MRQP_FW_COB_SYNC) {
    ++stats_.syncs;
  }
}

void DriveEmulator::on_nmt(Drive& d, const mrqp_fw_frame& f, TimeNs now) noexcept
{
  mrqp_fw_nmt_cmd cmd;
  std::uint8_t target = 0;
  if (mrqp_fw_nmt_unpack(&f, &cmd, &target) != MRQP_FW_OK || !mrqp_fw_nmt_addresses(target, d.cfg.node)) {
    return;
  }
  const mrqp_fw_nmt_state next = mrqp_fw_nmt_next_state(d.nmt, cmd);
  if (next == MRQP_FW_NMT_STATE_BOOTUP && (cmd == MRQP_FW_NMT_RESET_NODE || cmd == MRQP_FW_NMT_RESET_COMM)) {
    d.reset_od(cmd == MRQP_FW_NMT_RESET_COMM);
    if (cmd == MRQP_FW_NMT_RESET_NODE) {
      d.state = MRQP_FW_CIA402_NOT_READY_TO_SWITCH_ON;
      d.controlword = 0;
      d.rpdo_pending = false;
      d.target_position = d.q;
      d.error_code = 0;
    }
    d.nmt = MRQP_FW_NMT_STATE_BOOTUP;
    d.heartbeat_due = kNever;
    d.boot_at = now + cfg_.boot_delay;
    return;
  }
  d.nmt = next;
}

void DriveEmulator::on_sdo(Drive& d, const mrqp_fw_frame& f, TimeNs now) noexcept
{
  mrqp_fw_sdo_msg m;
  mrqp_fw_frame out;
  if (mrqp_fw_sdo_unpack(&f, &m) != MRQP_FW_OK) {
    (void)mrqp_fw_sdo_pack_abort(d.cfg.node, 1, 0, 0, MRQP_FW_SDO_ABORT_COMMAND, &out);
    send(out, now);
    return;
  }
  std::uint32_t abort = 0;
  Entry* e = d.find(m.index, m.subindex);
  if (m.kind == MRQP_FW_SDO_DOWNLOAD_INIT_REQ) {
    std::uint32_t v = 0;
    for (unsigned k = 0; k < m.n && k < 4; ++k) {
      v |= static_cast<std::uint32_t>(m.data[k]) << (8 * k);
    }
    if (!m.expedited) {
      abort = MRQP_FW_SDO_ABORT_COMMAND;
    } else if (e == nullptr) {
      abort = d.exists(m.index) ? MRQP_FW_SDO_ABORT_NO_SUBINDEX : MRQP_FW_SDO_ABORT_NO_OBJECT;
    } else if (m.n != e->size) {
      abort = MRQP_FW_SDO_ABORT_TYPE_LENGTH;
    } else {
      abort = d.check_write(*e, v);
    }
    if (abort == 0u) {
      e->value = v;
      if (m.index == 0x6060) {
        d.find(0x6061, 0)->value = v;
      }
      if (m.index == 0x1017) {
        d.heartbeat_due = v > 0u ? now + static_cast<TimeNs>(v) * 1000000 : kNever;
      }
      (void)mrqp_fw_sdo_pack_download_resp(d.cfg.node, m.index, m.subindex, &out);
    }
  } else if (m.kind == MRQP_FW_SDO_UPLOAD_INIT_REQ) {
    if (e == nullptr) {
      abort = d.exists(m.index) ? MRQP_FW_SDO_ABORT_NO_SUBINDEX : MRQP_FW_SDO_ABORT_NO_OBJECT;
    } else {
      std::uint8_t b[4];
      for (unsigned k = 0; k < 4; ++k) {
        b[k] = static_cast<std::uint8_t>((e->value >> (8 * k)) & 0xFFu);
      }
      (void)mrqp_fw_sdo_pack_upload_resp(d.cfg.node, m.index, m.subindex, b, e->size, &out);
    }
  } else {
    abort = MRQP_FW_SDO_ABORT_COMMAND;
  }
  if (abort != 0u) {
    (void)mrqp_fw_sdo_pack_abort(d.cfg.node, 1, m.index, m.subindex, abort, &out);
  }
  send(out, now);
}

void DriveEmulator::on_sync(Drive& d, TimeNs now) noexcept
{
  d.state = mrqp_fw_cia402_drive_event(d.state, MRQP_FW_CIA402_EV_FAULT_REACTION_DONE, nullptr);
  if (d.rpdo_pending) {
    d.rpdo_pending = false;
    const mrqp_fw_cia402_state before = d.state;
    d.state = mrqp_fw_cia402_drive_next(d.state, d.rpdo_controlword, d.controlword, nullptr);
    d.controlword = d.rpdo_controlword;
    double v = 0.0;
    if (mrqp_fw_arm_position_from_inc(&d.cfg.scale, d.rpdo_position, &v) == MRQP_FW_CONV_OK) {
      d.target_position = v;
    }
    if (mrqp_fw_arm_torque_from_permille(&d.cfg.scale, d.rpdo_torque, &v) == MRQP_FW_CONV_OK) {
      d.target_torque = v;
    }
    if (before == MRQP_FW_CIA402_FAULT && d.state != MRQP_FW_CIA402_FAULT) {
      d.error_code = 0;
      mrqp_fw_emcy e{};
      mrqp_fw_frame f;
      (void)mrqp_fw_emcy_pack(d.cfg.node, &e, &f);  // error reset
      send(f, now);
    }
  }
  if (d.state != MRQP_FW_CIA402_OPERATION_ENABLED) {
    d.target_position = d.q;  // follow the actual position while disabled
  }
  const std::int8_t mode = static_cast<std::int8_t>(d.value(0x6060, 0));
  std::int32_t pos = 0;
  std::int32_t vel = 0;
  std::int16_t torque = 0;
  (void)mrqp_fw_arm_position_to_inc(&d.cfg.scale, d.q, &pos);
  (void)mrqp_fw_arm_velocity_to_inc(&d.cfg.scale, d.qd, &vel);
  (void)mrqp_fw_arm_torque_to_permille(&d.cfg.scale, d.tau, &torque);
  mrqp_fw_frame f;
  if (d.tpdo1_ok()) {
    mrqp_fw_arm_tpdo1 t{mrqp_fw_cia402_statusword(d.state, MRQP_FW_SW_VOLTAGE_ENABLED), pos, torque};
    (void)mrqp_fw_arm_pack_tpdo1(d.cfg.node, &t, &f);
    send(f, now);
  }
  if (d.tpdo2_ok()) {
    mrqp_fw_arm_tpdo2 t{vel, d.error_code, mode};
    (void)mrqp_fw_arm_pack_tpdo2(d.cfg.node, &t, &f);
    send(f, now);
  }
}

}  // namespace mrqp::drive_emu
