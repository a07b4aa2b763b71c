// mrqp drivers -- bus-load budget (setup only).
#include "mrqp/drivers/bus_budget.hpp"

#include <cstdio>
#include <utility>

#include "mrqp/firmware_if/frame.h"
#include "mrqp/firmware_if/hand_fd_frame.h"
#include "mrqp/firmware_if/imu.h"

namespace mrqp::drivers {

namespace {

std::string fmt(const char* format, double v) {
  char buf[64];
  std::snprintf(buf, sizeof(buf), format, v);
  return buf;
}

std::string rateStr(std::uint32_t bps) {
  if (bps % 1000000u == 0u) {
    return std::to_string(bps / 1000000u);
  }
  if (bps % 1000u == 0u) {
    return fmt("%g", static_cast<double>(bps) / 1e6);
  }
  return fmt("%.3f", static_cast<double>(bps) / 1e6);
}

const char* formatStr(FrameFormat f) {
  switch (f) {
    case FrameFormat::Classic:
      return "classic";
    case FrameFormat::Fd:
      return "FD";
    case FrameFormat::FdBrs:
      return "FD+BRS";
  }
  return "?";
}

double frameNs(mrqp_fw_frame_bits bits, std::uint32_t nominal, std::uint32_t data) {
  double ns = static_cast<double>(bits.nominal_bits) * 1e9 / static_cast<double>(nominal);
  if (bits.data_bits > 0u) {
    ns += static_cast<double>(bits.data_bits) * 1e9 / static_cast<double>(data > 0u ? data : nominal);
  }
  return ns;
}

std::string bitsStr(mrqp_fw_frame_bits b) {
  if (b.data_bits == 0u) {
    return std::to_string(b.nominal_bits);
  }
  return std::to_string(b.nominal_bits) + "+" + std::to_string(b.data_bits);
}

}  // namespace

std::string busSpecLabel(const BusSpec& spec) {
  if (spec.data_bps > 0u) {
    return "CAN FD " + rateStr(spec.nominal_bps) + "/" + rateStr(spec.data_bps) + " Mbit/s";
  }
  return "classic " + rateStr(spec.nominal_bps) + " Mbit/s";
}

BusBudget::BusBudget(BusSpec spec) : spec_(std::move(spec)) {
  if (spec_.nominal_bps == 0u) {
    error_ = "nominal bit rate is 0";
  } else if (!(spec_.cycle_hz > 0.0)) {
    error_ = "cycle rate must be > 0 Hz";
  } else if (!(spec_.limit > 0.0 && spec_.limit <= 1.0)) {
    error_ = "utilisation limit must be in (0, 1]";
  }
}

void BusBudget::add(const std::string& label, std::uint32_t count, unsigned len, FrameFormat format,
                    double period_s) {
  BudgetLine line;
  line.label = label;
  line.count = count;
  line.format = format;
  line.period_s = period_s;
  if (format == FrameFormat::Classic) {
    if (len > MRQP_FW_CAN_CLASSIC_MAX_LEN) {
      error_ = "'" + label + "': a classic frame carries at most 8 bytes, not " + std::to_string(len);
      len = MRQP_FW_CAN_CLASSIC_MAX_LEN;
    }
    line.bits_min = mrqp_fw_bits_classic(len, 0);
    line.bits_worst = mrqp_fw_bits_classic(len, 1);
  } else {
    if (spec_.data_bps == 0u && error_.empty()) {
      error_ = "'" + label + "': CAN FD frames on a classic bus";
    }
    const unsigned rounded = mrqp_fw_fd_len_round_up(len);
    if (rounded == 0u || len > MRQP_FW_CAN_FD_MAX_LEN) {
      error_ = "'" + label + "': a CAN FD frame carries at most 64 bytes, not " + std::to_string(len);
    }
    len = rounded == 0u ? MRQP_FW_CAN_FD_MAX_LEN : rounded;
    const int brs = format == FrameFormat::FdBrs ? 1 : 0;
    line.bits_min = mrqp_fw_bits_fd(len, brs, 0);
    line.bits_worst = mrqp_fw_bits_fd(len, brs, 1);
  }
  if (period_s < 0.0) {
    error_ = "'" + label + "': negative period";
  }
  line.len = static_cast<std::uint8_t>(len);
  line.ns_min = frameNs(line.bits_min, spec_.nominal_bps, spec_.data_bps);
  line.ns_worst = frameNs(line.bits_worst, spec_.nominal_bps, spec_.data_bps);
  const double cycle_s = spec_.cycle_hz > 0.0 ? 1.0 / spec_.cycle_hz : 0.0;
  line.per_cycle =
      period_s > 0.0 ? static_cast<double>(count) * cycle_s / period_s : static_cast<double>(count);
  lines_.push_back(line);
}

void BusBudget::addCyclic(const std::string& label, std::uint32_t count, unsigned len, FrameFormat format) {
  add(label, count, len, format, 0.0);
}

void BusBudget::addPeriodic(const std::string& label, std::uint32_t count, unsigned len, FrameFormat format,
                            double period_s) {
  if (!(period_s > 0.0)) {
    error_ = "'" + label + "': the period must be > 0 s";
    period_s = 1.0;
  }
  add(label, count, len, format, period_s);
}

void BusBudget::addSync() { addCyclic("SYNC", 1, 0, FrameFormat::Classic); }

void BusBudget::addArmDrives(std::uint32_t n, bool tpdo2) {
  if (n == 0u) {
    return;
  }
  addCyclic("arm RPDO1 (controlword, target)", n, 8, FrameFormat::Classic);
  addCyclic("arm TPDO1 (statusword, position, torque)", n, 8, FrameFormat::Classic);
  if (tpdo2) {
    addCyclic("arm TPDO2 (velocity, error code, mode)", n, 7, FrameFormat::Classic);
  }
}

void BusBudget::addHeartbeats(std::uint32_t n, double period_s) {
  if (n > 0u) {
    addPeriodic("heartbeat", n, 1, FrameFormat::Classic, period_s);
  }
}

void BusBudget::addMitMotors(std::uint32_t n) {
  if (n == 0u) {
    return;
  }
  addCyclic("MIT command", n, 8, FrameFormat::Classic);
  addCyclic("MIT reply", n, 6, FrameFormat::Classic);
}

void BusBudget::addHandBoard(std::uint32_t joints) {
  if (joints > MRQP_FW_HAND_MAX_JOINTS) {
    error_ = "a hand board drives at most 32 joints, not " + std::to_string(joints);
    joints = MRQP_FW_HAND_MAX_JOINTS;
  }
  std::uint32_t left = joints;
  do {
    const std::uint32_t n = left > MRQP_FW_HAND_FD_MAX_JOINTS ? MRQP_FW_HAND_FD_MAX_JOINTS : left;
    addCyclic("hand FD command (" + std::to_string(n) + " joints)", 1, mrqp_fw_hand_cmd_len(n),
              FrameFormat::FdBrs);
    addCyclic("hand FD feedback (" + std::to_string(n) + " joints)", 1, mrqp_fw_hand_fb_len(n),
              FrameFormat::FdBrs);
    left -= n;
  } while (left > 0u);
}

void BusBudget::addFtClassic(std::uint32_t n) {
  if (n > 0u) {
    addCyclic("F/T forces + moments", 2u * n, 8, FrameFormat::Classic);
  }
}

void BusBudget::addFtFd(std::uint32_t n) {
  if (n > 0u) {
    addCyclic("F/T FD frame", n, 32, FrameFormat::FdBrs);
  }
}

void BusBudget::addImuFd(std::uint32_t n) {
  if (n > 0u) {
    addCyclic("IMU FD frame", n, MRQP_FW_IMU_FD_LEN, FrameFormat::FdBrs);
  }
}

BudgetResult BusBudget::result() const {
  BudgetResult r;
  r.limit = spec_.limit;
  r.cycle_ns = spec_.cycle_hz > 0.0 ? 1e9 / spec_.cycle_hz : 0.0;
  if (!error_.empty()) {
    r.valid = false;
    r.fits = false;
    r.error = error_;
  }
  for (const BudgetLine& l : lines_) {
    r.frames_per_cycle += l.per_cycle;
    r.nominal_bits_min += l.per_cycle * l.bits_min.nominal_bits;
    r.nominal_bits_worst += l.per_cycle * l.bits_worst.nominal_bits;
    r.data_bits_min += l.per_cycle * l.bits_min.data_bits;
    r.data_bits_worst += l.per_cycle * l.bits_worst.data_bits;
    r.time_min_ns += l.per_cycle * l.ns_min;
    r.time_worst_ns += l.per_cycle * l.ns_worst;
  }
  if (r.cycle_ns > 0.0) {
    r.utilisation_min = r.time_min_ns / r.cycle_ns;
    r.utilisation_worst = r.time_worst_ns / r.cycle_ns;
  }
  if (r.valid) {
    // A tiny tolerance so that a budget exactly at the limit (computed in floating point) fits.
    r.fits = r.utilisation_worst <= spec_.limit + 1e-12;
  }
  return r;
}

bool BusBudget::check(std::string* message) const {
  const BudgetResult r = result();
  const std::string head =
      "bus '" + spec_.name + "' (" + busSpecLabel(spec_) + ", " + fmt("%g", spec_.cycle_hz) + " Hz)";
  if (!r.valid) {
    if (message != nullptr) {
      *message = head + ": invalid budget: " + r.error;
    }
    return false;
  }
  if (r.fits) {
    if (message != nullptr) {
      *message = head + ": worst case " + fmt("%.1f", r.time_worst_ns / 1e3) + " us per " +
                 fmt("%.1f", r.cycle_ns / 1e3) + " us cycle = " + fmt("%.1f", 100.0 * r.utilisation_worst) +
                 " % of the bus, within the " + fmt("%.1f", 100.0 * spec_.limit) + " % limit";
    }
    return true;
  }
  if (message != nullptr) {
    const double allowed_ns = spec_.limit * r.cycle_ns;
    *message = head + ": worst case " + fmt("%.1f", r.time_worst_ns / 1e3) + " us of frames per " +
               fmt("%.1f", r.cycle_ns / 1e3) + " us cycle = " + fmt("%.1f", 100.0 * r.utilisation_worst) +
               " % of the bus; the limit is " + fmt("%.1f", 100.0 * spec_.limit) + " %: over by " +
               fmt("%.1f", 100.0 * (r.utilisation_worst - spec_.limit)) + " percentage points (" +
               fmt("%.1f", (r.time_worst_ns - allowed_ns) / 1e3) + " us too much per cycle, " +
               fmt("%.2f", r.time_worst_ns / allowed_ns) +
               " times what the limit allows): use more buses, a lower cycle rate or fewer frames";
  }
  return false;
}

std::string BusBudget::report() const {
  const BudgetResult r = result();
  std::string out = "bus '" + spec_.name + "': " + busSpecLabel(spec_) + ", " + fmt("%g", spec_.cycle_hz) +
                    " Hz (cycle " + fmt("%.1f", r.cycle_ns / 1e3) + " us), limit " +
                    fmt("%.1f", 100.0 * spec_.limit) + " % (worst-case stuffing)\n";
  for (const BudgetLine& l : lines_) {
    char line[256];
    std::snprintf(
        line, sizeof(line), "  %-44s %7.2f x %2u B %-7s %7s..%-7s bits %6.1f..%6.1f us/frame\n",
        (l.label + (l.period_s > 0.0 ? " (every " + fmt("%g", l.period_s * 1e3) + " ms)" : "")).c_str(),
        l.per_cycle, static_cast<unsigned>(l.len), formatStr(l.format), bitsStr(l.bits_min).c_str(),
        bitsStr(l.bits_worst).c_str(), l.ns_min / 1e3, l.ns_worst / 1e3);
    out += line;
  }
  char total[256];
  std::snprintf(total, sizeof(total),
                "  total: %.2f frames/cycle, %.1f..%.1f us per cycle = %.1f..%.1f %% of the bus",
                r.frames_per_cycle, r.time_min_ns / 1e3, r.time_worst_ns / 1e3, 100.0 * r.utilisation_min,
                100.0 * r.utilisation_worst);
  out += total;
  if (!r.valid) {
    out += " -> INVALID: " + r.error + "\n";
  } else if (r.fits) {
    out += " -> fits\n";
  } else {
    out += " -> REFUSED: over the limit by " + fmt("%.1f", 100.0 * (r.utilisation_worst - spec_.limit)) +
           " percentage points\n";
  }
  return out;
}

}  // namespace mrqp::drivers
