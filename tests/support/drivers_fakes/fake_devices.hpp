// Fake hand actuators, hand controller board, force/torque sensor and IMU for the driver tests,
// built from the firmware_if frames, attached to SimNodes as their firmware. Allocation-free.
#pragma once

#include <mrqp/firmware_if/firmware_if.h>
#include <mrqp/drivers/sim_bus.hpp>

#include <array>
#include <cstdint>

namespace drvtest {

using mrqp::drivers::ReceiveResult;
using mrqp::drivers::RxFrame;
using mrqp::drivers::SimNode;
using mrqp::drivers::TimeNs;

/// MIT-mode motors: one SimNode may host several motors (as several controllers would).
class FakeMitMotors final : public mrqp::drivers::SimListener {
 public:
  static constexpr std::size_t kMax = 32;

  FakeMitMotors(SimNode& node, TimeNs response_delay = 30000) : node_(node), delay_(response_delay) {
    node_.setListener(this);
  }
  /// Adds a motor with `id` (ranges: the defaults).
  void add(std::uint8_t id) noexcept {
    motors_[count_].id = id;
    ++count_;
  }
  void setSilent(std::uint8_t id, bool silent) noexcept {
    if (Motor* m = find(id)) {
      m->silent = silent;
    }
  }
  bool enabled(std::uint8_t id) const noexcept {
    for (std::size_t i = 0; i < count_; ++i) {
      if (motors_[i].id == id) {
        return motors_[i].enabled;
      }
    }
    return false;
  }
  float position(std::uint8_t id) const noexcept {
    for (std::size_t i = 0; i < count_; ++i) {
      if (motors_[i].id == id) {
        return motors_[i].p;
      }
    }
    return 0.0f;
  }
  unsigned frames(std::uint8_t id) const noexcept {
    for (std::size_t i = 0; i < count_; ++i) {
      if (motors_[i].id == id) {
        return motors_[i].frames;
      }
    }
    return 0;
  }
  void setPosition(std::uint8_t id, float p) noexcept {
    if (Motor* m = find(id)) {
      m->p = p;
    }
  }

  void onReceive(SimNode&, ReceiveResult kind, const RxFrame& rx) noexcept override {
    if (kind != ReceiveResult::Frame) {
      return;
    }
    const mrqp_fw_mit_kind k = mrqp_fw_mit_classify(&rx.frame);
    if (k == MRQP_FW_MIT_KIND_INVALID) {
      return;
    }
    Motor* m = find(static_cast<std::uint8_t>(rx.frame.id));
    if (m == nullptr) {
      return;
    }
    ++m->frames;
    switch (k) {
      case MRQP_FW_MIT_KIND_ENABLE:
        m->enabled = true;
        break;
      case MRQP_FW_MIT_KIND_DISABLE:
        m->enabled = false;
        break;
      case MRQP_FW_MIT_KIND_ZERO:
        m->p = 0.0f;
        break;
      case MRQP_FW_MIT_KIND_COMMAND: {
        mrqp_fw_mit_cmd c;
        if (mrqp_fw_mit_unpack_cmd(&ranges_, &rx.frame, nullptr, &c) == MRQP_FW_OK && m->enabled) {
          // Ideal actuator: reaches the stiffness-weighted target, torque = the commanded effort.
          m->t = c.kp * (c.p - m->p) + c.t;
          if (c.kp > 0.0f) {
            m->p = c.p;
          }
          m->v = c.v;
        }
        break;
      }
      case MRQP_FW_MIT_KIND_INVALID:
        break;
    }
    if (m->silent) {
      return;
    }
    mrqp_fw_mit_reply r{m->id, m->p, m->v, m->t};
    mrqp_fw_frame f;
    if (!mrqp_fw_pack_failed(mrqp_fw_mit_pack_reply(&ranges_, &r, &f))) {
      (void)node_.sendAt(f, rx.timestamp + delay_);
    }
  }

 private:
  struct Motor {
    std::uint8_t id = 0;
    bool enabled = false;
    bool silent = false;
    float p = 0.0f;
    float v = 0.0f;
    float t = 0.0f;
    unsigned frames = 0;
  };
  Motor* find(std::uint8_t id) noexcept {
    for (std::size_t i = 0; i < count_; ++i) {
      if (motors_[i].id == id) {
        return &motors_[i];
      }
    }
    return nullptr;
  }
  SimNode& node_;
  TimeNs delay_;
  mrqp_fw_mit_ranges ranges_ = MRQP_FW_MIT_RANGES_DEFAULT_INIT;
  std::array<Motor, kMax> motors_{};
  std::size_t count_ = 0;
};

/// A hand controller board on CAN FD: answers every command frame with the feedback frame of
/// the same joints, counter +1 per feedback frame.
class FakeHandBoard final : public mrqp::drivers::SimListener {
 public:
  FakeHandBoard(SimNode& node, unsigned board, unsigned joints, TimeNs response_delay = 20000)
      : node_(node), board_(board), joints_(joints), delay_(response_delay) {
    node_.setListener(this);
  }
  void setSilent(bool s) noexcept { silent_ = s; }
  void setStatusExtra(std::uint8_t bits) noexcept { extra_status_ = bits; }
  /// Skip the counter by `n` before the next feedback frame (lost frames).
  void skipCounter(std::uint8_t n) noexcept { counter_ = static_cast<std::uint8_t>(counter_ + n); }
  /// Do not apply commands (the echo stops moving).
  void setFrozen(bool f) noexcept { frozen_ = f; }
  std::uint8_t mode() const noexcept { return mode_; }
  float position(unsigned j) const noexcept { return joints_state_[j].position; }
  unsigned joints() const noexcept { return joints_; }
  unsigned commands() const noexcept { return commands_; }

  void onReceive(SimNode&, ReceiveResult kind, const RxFrame& rx) noexcept override {
    if (kind != ReceiveResult::Frame || rx.frame.id != MRQP_FW_HAND_FD_CMD_ID_BASE + board_) {
      return;
    }
    mrqp_fw_hand_cmd c;
    if (mrqp_fw_hand_unpack_cmd(&scale_, &rx.frame, board_, &c) != MRQP_FW_OK) {
      status_ |= MRQP_FW_HAND_STATUS_CRC_ERROR_SEEN;
      return;
    }
    ++commands_;
    if (!frozen_) {
      seq_echo_ = c.seq;
      mode_ = c.mode;
      for (unsigned j = 0; j < c.count; ++j) {
        mrqp_fw_hand_joint& js = joints_state_[c.first_joint + j];
        if (mode_ == MRQP_FW_HAND_MODE_POSITION) {
          js.position = c.joint[j].position;
          js.velocity = c.joint[j].velocity;
          js.torque = c.joint[j].torque;
        } else if (mode_ == MRQP_FW_HAND_MODE_TORQUE) {
          js.torque = c.joint[j].torque;
        }
      }
    }
    if (silent_) {
      return;
    }
    mrqp_fw_hand_fb fb{};
    fb.cmd_seq_echo = seq_echo_;
    fb.counter = ++counter_;
    fb.mode = mode_;
    fb.status = static_cast<std::uint8_t>(
        (mode_ != MRQP_FW_HAND_MODE_DISABLED ? MRQP_FW_HAND_STATUS_ENABLED : 0u) | status_ | extra_status_);
    fb.first_joint = c.first_joint;
    fb.count = c.count;
    for (unsigned j = 0; j < c.count; ++j) {
      fb.joint[j] = joints_state_[c.first_joint + j];
    }
    mrqp_fw_frame f;
    if (!mrqp_fw_pack_failed(mrqp_fw_hand_pack_fb(&scale_, board_, &fb, &f, nullptr))) {
      (void)node_.sendAt(f, rx.timestamp + delay_);
    }
  }

 private:
  SimNode& node_;
  unsigned board_;
  unsigned joints_;
  TimeNs delay_;
  mrqp_fw_hand_scale scale_ = MRQP_FW_HAND_SCALE_DEFAULT_INIT;
  std::array<mrqp_fw_hand_joint, MRQP_FW_HAND_MAX_JOINTS> joints_state_{};
  std::uint16_t seq_echo_ = 0;
  std::uint8_t counter_ = 0;
  std::uint8_t mode_ = MRQP_FW_HAND_MODE_DISABLED;
  std::uint8_t status_ = 0;
  std::uint8_t extra_status_ = 0;
  bool silent_ = false;
  bool frozen_ = false;
  unsigned commands_ = 0;
};

/// A force/torque sensor: samples on SYNC, sends the classic pair or the FD frame, handles tare.
class FakeFtSensor final : public mrqp::drivers::SimListener {
 public:
  FakeFtSensor(SimNode& node, unsigned node_id, bool fd, TimeNs response_delay = 15000)
      : node_(node), id_(node_id), fd_(fd), delay_(response_delay) {
    node_.setListener(this);
    scale_ = fd ? mrqp_fw_ft_scale MRQP_FW_FT_SCALE_FD_DEFAULT_INIT
                : mrqp_fw_ft_scale MRQP_FW_FT_SCALE_CLASSIC_DEFAULT_INIT;
  }
  void setWrench(const std::array<double, 6>& w) noexcept { wrench_ = w; }
  void setSilent(bool s) noexcept { silent_ = s; }
  /// Send only the forces half of the next `n` samples.
  void dropMoments(unsigned n) noexcept { drop_moments_ = n; }
  void skipSeq(std::uint8_t n) noexcept { seq_ = static_cast<std::uint8_t>(seq_ + n); }
  void setStatusExtra(std::uint8_t bits) noexcept { extra_status_ = bits; }
  bool tared() const noexcept { return tared_; }
  unsigned syncs() const noexcept { return syncs_; }

  void onReceive(SimNode&, ReceiveResult kind, const RxFrame& rx) noexcept override {
    if (kind != ReceiveResult::Frame) {
      return;
    }
    const mrqp_fw_frame& f = rx.frame;
    std::uint8_t cmd = 0;
    if (f.id == MRQP_FW_COB_RPDO1_BASE + id_ && mrqp_fw_ft_unpack_tare(&f, id_, &cmd) == MRQP_FW_OK) {
      if (cmd == MRQP_FW_FT_CMD_TARE) {
        tared_ = true;
        for (std::size_t k = 0; k < 6; ++k) {
          offset_[k] = wrench_[k];
        }
      } else {
        tared_ = false;
        offset_ = {};
      }
      return;
    }
    if (f.id != MRQP_FW_COB_SYNC || silent_) {
      return;
    }
    ++syncs_;
    mrqp_fw_ft_sample s{};
    for (std::size_t k = 0; k < 6; ++k) {
      s.wrench[k] = wrench_[k] - offset_[k];
    }
    s.seq = ++seq_;
    s.status = static_cast<std::uint8_t>((tared_ ? MRQP_FW_FT_STATUS_TARED : 0u) | extra_status_);
    if (fd_) {
      mrqp_fw_frame out;
      if (!mrqp_fw_pack_failed(mrqp_fw_ft_pack_fd(&scale_, id_, &s, &out))) {
        (void)node_.sendAt(out, rx.timestamp + delay_);
      }
      return;
    }
    mrqp_fw_frame forces;
    mrqp_fw_frame moments;
    if (!mrqp_fw_pack_failed(mrqp_fw_ft_pack_classic(&scale_, id_, &s, &forces, &moments))) {
      (void)node_.sendAt(forces, rx.timestamp + delay_);
      if (drop_moments_ > 0) {
        --drop_moments_;
      } else {
        (void)node_.sendAt(moments, rx.timestamp + delay_);
      }
    }
  }

 private:
  SimNode& node_;
  unsigned id_;
  bool fd_;
  TimeNs delay_;
  mrqp_fw_ft_scale scale_{};
  std::array<double, 6> wrench_{};
  std::array<double, 6> offset_{};
  std::uint8_t seq_ = 0;
  std::uint8_t extra_status_ = 0;
  unsigned drop_moments_ = 0;
  unsigned syncs_ = 0;
  bool tared_ = false;
  bool silent_ = false;
};

/// An IMU: on SYNC sends one FD sample frame (firmware_if/imu.h) of the values set here.
class FakeImu final : public mrqp::drivers::SimListener {
 public:
  FakeImu(SimNode& node, unsigned node_id, TimeNs response_delay = 15000)
      : node_(node), id_(node_id), delay_(response_delay) {
    node_.setListener(this);
    sample_.orientation[0] = 1.0;
  }
  mrqp_fw_imu_sample& sample() noexcept { return sample_; }
  void setSilent(bool s) noexcept { silent_ = s; }
  void skipSeq(std::uint8_t n) noexcept { seq_ = static_cast<std::uint8_t>(seq_ + n); }
  unsigned syncs() const noexcept { return syncs_; }

  void onReceive(SimNode&, ReceiveResult kind, const RxFrame& rx) noexcept override {
    if (kind != ReceiveResult::Frame || rx.frame.id != MRQP_FW_COB_SYNC || silent_) {
      return;
    }
    ++syncs_;
    mrqp_fw_imu_sample s = sample_;
    s.seq = ++seq_;
    mrqp_fw_frame out;
    if (!mrqp_fw_pack_failed(mrqp_fw_imu_pack(&scale_, id_, &s, &out))) {
      (void)node_.sendAt(out, rx.timestamp + delay_);
    }
  }

 private:
  SimNode& node_;
  unsigned id_;
  TimeNs delay_;
  mrqp_fw_imu_scale scale_ = MRQP_FW_IMU_SCALE_DEFAULT_INIT;
  mrqp_fw_imu_sample sample_{};
  std::uint8_t seq_ = 0;
  unsigned syncs_ = 0;
  bool silent_ = false;
};

}  // namespace drvtest
