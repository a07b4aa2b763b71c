// bench_codec: the cost per frame of the CAN wire codec (firmware_if, docs/protocol.md), and the
// cost of one control cycle of the drivers for 7 arm drives + 20 MIT hand motors + 2 wrist
// force/torque sensors.
//
// Benchmarks:
//   BM_encode/<message>, BM_decode/<message>
//       One pack or unpack of one message per iteration (firmware_if C functions, called as the
//       host or the drive firmware calls them). Each benchmark cycles through 1024 different inputs
//       drawn from a fixed seed (values within the wire ranges, node ids, commands and lengths
//       varied), so that nothing is constant. Before timing, every input is packed and the packed
//       frames are decoded: a failure aborts that benchmark (SkipWithError). Messages of two
//       frames (hand FD 20 joints = 11 + 9 joints; force/torque classic = forces + moments) count
//       two frames per iteration.
//   BM_cycle/codec
//       The host's codec work of one cycle for that device set, without drivers: encode 7 RPDO1
//       (SI), 1 SYNC, 20 MIT commands; decode 7 TPDO1 and 7 TPDO2 (to SI), 20 MIT replies, 2
//       force/torque classic pairs. 28 + 38 = 66 frames.
//   BM_cycle/drivers_host
//       One cycle of ArmDriver (7 drives, CSP) + FtSensorDriver (2 classic sensors, same bus) +
//       MitHandDriver (20 motors, own bus): router poll, update, setpoints, transmit. The replies
//       are one steady-state cycle recorded over the simulated bus after boot and replayed by a
//       bus that discards what is sent (positions and sensor sequence numbers advanced per cycle):
//       the host-side cost only, the same 66 frames.
//   BM_cycle/drivers_sim_bus
//       The same cycle over the in-process SimBus with the fake devices of tests/drivers: adds the
//       wire model and the emulated device firmware (which decode the commands and encode the
//       replies).
//   The driver cycles use a simulated period of 10 ms so that a single classic bus per device
//   class carries all frames (at 1 kHz this set needs several buses, docs/protocol.md "Bus
//   load"); the CPU cost of a cycle does not depend on the simulated period. Heartbeats are off
//   (producer heartbeat 0) so that the replayed cycle stays valid; any fault flag raised during
//   the timed cycles aborts the benchmark.
//
// Counters: items_per_second = frames per second; per_frame = CPU time per frame (printed in
// seconds with an SI prefix, e.g. 12.3n = 12.3 ns). Each benchmark also reports a "max"
// aggregate when run with --benchmark_repetitions.
//
//   bench_codec --benchmark_repetitions=10 --benchmark_report_aggregates_only=true
//               --benchmark_filter='BM_(en|de)code/mit'
#include <benchmark/benchmark.h>

#include <mrqp/firmware_if/firmware_if.h>
#include <mrqp/drivers/arm_driver.hpp>
#include <mrqp/drivers/bus.hpp>
#include <mrqp/drivers/bus_router.hpp>
#include <mrqp/drivers/faults.hpp>
#include <mrqp/drivers/ft_sensor_driver.hpp>
#include <mrqp/drivers/mit_hand_driver.hpp>
#include <mrqp/drivers/sim_bus.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "fake_cia402_drive.hpp"
#include "fake_devices.hpp"

namespace {

/// Distinct inputs per benchmark (a power of two: the index wraps with a mask): more bit patterns
/// than a branch predictor learns (the MIT and hand FD codecs branch on every bit), few enough
/// for the inputs and frames to stay in L2.
constexpr std::size_t kRing = 1024;
constexpr std::size_t kMask = kRing - 1;

/// Fixed-seed source of input values.
struct Rng {
  explicit Rng(std::uint32_t seed) : gen(seed) {}
  double real(double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(gen); }
  float realf(float lo, float hi) { return static_cast<float>(real(lo, hi)); }
  unsigned uint(unsigned lo, unsigned hi) { return std::uniform_int_distribution<unsigned>(lo, hi)(gen); }
  std::int32_t int32(std::int32_t lo, std::int32_t hi) {
    return std::uniform_int_distribution<std::int32_t>(lo, hi)(gen);
  }
  std::uint8_t byte() { return static_cast<std::uint8_t>(uint(0, 255)); }
  std::mt19937 gen;
};

/// Counters common to every benchmark: frames per second and CPU time per frame.
void report(benchmark::State& state, int frames) {
  state.SetItemsProcessed(state.iterations() * frames);
  state.counters["frames_per_iter"] = frames;
  state.counters["per_frame"] =
      benchmark::Counter(frames, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

/// Adds the "max" aggregate (slowest repetition) to a benchmark.
benchmark::internal::Benchmark* withMax(benchmark::internal::Benchmark* b) {
  return b->ComputeStatistics("max", [](const std::vector<double>& v) {
    return v.empty() ? 0.0 : *std::max_element(v.begin(), v.end());
  });
}

/// Times fn(i) for i = 0, 1, ... (mod kRing). fn returns non-zero on a failure (a pack error bit
/// or an unpack error code); the ring is checked once before timing.
template <class Fn>
void run(benchmark::State& state, int frames, Fn&& fn) {
  for (std::size_t i = 0; i < kRing; ++i) {
    if (fn(i) != 0u) {
      state.SkipWithError(("input " + std::to_string(i) + " fails").c_str());
      return;
    }
  }
  std::uint32_t failed = 0;
  std::size_t i = 0;
  for (auto _ : state) {
    failed |= fn(i);
    i = (i + 1) & kMask;
  }
  benchmark::DoNotOptimize(failed);
  if (failed != 0u) {
    state.SkipWithError("a frame failed during the timed loop");
    return;
  }
  report(state, frames);
}

std::uint32_t packErr(mrqp_fw_pack_flags flags) { return flags & MRQP_FW_PACK_ERR_MASK; }
std::uint32_t unpackErr(mrqp_fw_err err) { return static_cast<std::uint32_t>(err); }

/// One encode and one decode benchmark of a message: inputs[i] -> frames[i][0..F) -> decoded.
/// `make(rng)` draws an input, `pack(input, frames)` encodes it, `unpack(frames, input)` decodes
/// (the input is passed for what the receiver knows in advance, e.g. its node id).
template <class In, std::size_t F, class Make, class Pack, class Unpack>
struct Message {
  std::array<In, kRing> in;
  std::array<std::array<mrqp_fw_frame, F>, kRing> frames;
  Pack pack;
  Unpack unpack;

  Message(std::uint32_t seed, Make make, Pack p, Unpack u) : pack(p), unpack(u) {
    Rng rng(seed);
    for (std::size_t i = 0; i < kRing; ++i) {
      in[i] = make(rng, i);
      for (auto& f : frames[i]) {
        mrqp_fw_frame_clear(&f);
      }
      (void)pack(in[i], frames[i].data());
    }
  }
  void encode(benchmark::State& state) {
    std::array<mrqp_fw_frame, F> out{};
    run(state, static_cast<int>(F), [&](std::size_t i) {
      const std::uint32_t e = packErr(pack(in[i], out.data()));
      benchmark::DoNotOptimize(out);
      return e;
    });
  }
  void decode(benchmark::State& state) {
    run(state, static_cast<int>(F),
        [&](std::size_t i) { return unpackErr(unpack(frames[i].data(), in[i])); });
  }
};

/// Registers BM_encode/<name> and (with decode) BM_decode/<name> for one message kind.
template <class In, std::size_t F, class Make, class Pack, class Unpack>
void addMessage(const char* name, std::uint32_t seed, Make make, Pack pack, Unpack unpack, bool decode = true,
                bool encode = true) {
  using M = Message<In, F, Make, Pack, Unpack>;
  auto msg = std::make_shared<M>(seed, make, pack, unpack);
  if (encode) {
    withMax(benchmark::RegisterBenchmark((std::string("BM_encode/") + name).c_str(),
                                         [msg](benchmark::State& s) { msg->encode(s); }));
  }
  if (decode) {
    withMax(benchmark::RegisterBenchmark((std::string("BM_decode/") + name).c_str(),
                                         [msg](benchmark::State& s) { msg->decode(s); }));
  }
}

// ---- the messages ------------------------------------------------------------------------------

const mrqp_fw_arm_scale kArmScale = MRQP_FW_ARM_SCALE_DEFAULT_INIT;
const mrqp_fw_mit_ranges kMitRanges = MRQP_FW_MIT_RANGES_DEFAULT_INIT;
const mrqp_fw_hand_scale kHandScale = MRQP_FW_HAND_SCALE_DEFAULT_INIT;
const mrqp_fw_ft_scale kFtClassic = MRQP_FW_FT_SCALE_CLASSIC_DEFAULT_INIT;
const mrqp_fw_ft_scale kFtFd = MRQP_FW_FT_SCALE_FD_DEFAULT_INIT;

unsigned nodeOf(std::size_t i) { return 1u + static_cast<unsigned>((i * 37u) % 127u); }

// CANopen NMT / SYNC / heartbeat / EMCY.
struct NmtIn {
  mrqp_fw_nmt_cmd cmd;
  unsigned node;
};
struct HeartbeatIn {
  unsigned node;
  mrqp_fw_nmt_state state;
};
struct EmcyIn {
  unsigned node;
  mrqp_fw_emcy emcy;
};

// SDO: one struct for every kind.
struct SdoIn {
  unsigned node;
  std::uint16_t index;
  std::uint8_t sub;
  std::uint32_t value;
  unsigned n;
  int from_server;
  unsigned toggle;
  int last;
  std::array<std::uint8_t, 7> data;
};

struct ArmPdoIn {
  unsigned node;
  mrqp_fw_arm_rpdo1 rpdo1;
  mrqp_fw_arm_tpdo1 tpdo1;
  mrqp_fw_arm_tpdo2 tpdo2;
  double position_rad;
  double torque_nm;
};

struct MitIn {
  unsigned id;
  mrqp_fw_mit_cmd cmd;
  mrqp_fw_mit_reply reply;
  mrqp_fw_mit_kind special;
};

/// A 20-joint hand: frame 0 = joints 0..10, frame 1 = joints 11..19.
struct HandIn {
  unsigned board;
  std::array<mrqp_fw_hand_cmd, 2> cmd;
  std::array<mrqp_fw_hand_fb, 2> fb;
};

struct FtIn {
  unsigned node;
  mrqp_fw_ft_sample classic;
  mrqp_fw_ft_sample fd;
  unsigned tare;
};

SdoIn makeSdo(Rng& r, std::size_t i) {
  SdoIn s{};
  s.node = nodeOf(i);
  s.index = static_cast<std::uint16_t>(0x6000u + r.uint(0, 0xFFF));
  s.sub = static_cast<std::uint8_t>(r.uint(0, 8));
  s.value = static_cast<std::uint32_t>(r.uint(0, 0xFFFFFFFFu));
  static constexpr unsigned kExpedited[3] = {1, 2, 4};
  s.n = kExpedited[i % 3];
  s.from_server = static_cast<int>(i & 1u);
  s.toggle = static_cast<unsigned>((i >> 1) & 1u);
  s.last = (i % 5) == 0 ? 1 : 0;
  for (auto& b : s.data) {
    b = r.byte();
  }
  return s;
}

mrqp_fw_sdo_msg g_sdo_msg;  // decode output, outside the loop's registers

std::uint32_t sdoDecode(const mrqp_fw_frame* f) {
  const mrqp_fw_err e = mrqp_fw_sdo_unpack(f, &g_sdo_msg);
  benchmark::DoNotOptimize(g_sdo_msg);
  return unpackErr(e);
}

ArmPdoIn makeArm(Rng& r, std::size_t i) {
  ArmPdoIn a{};
  a.node = 1u + static_cast<unsigned>(i % 7u);
  static constexpr std::uint16_t kCw[4] = {0x0006, 0x0007, 0x000F, 0x010F};
  a.rpdo1 = {kCw[i % 4], r.int32(-2000000, 2000000), static_cast<std::int16_t>(r.int32(-3000, 3000))};
  a.tpdo1 = {static_cast<std::uint16_t>(0x1237u + (i & 1u) * 0x400u), r.int32(-2000000, 2000000),
             static_cast<std::int16_t>(r.int32(-3000, 3000))};
  a.tpdo2 = {r.int32(-500000, 500000), static_cast<std::uint16_t>((i % 9u) == 0u ? 0x8611u : 0u),
             static_cast<std::int8_t>((i & 1u) ? MRQP_FW_MODE_CSP : MRQP_FW_MODE_CST)};
  a.position_rad = r.real(-3.0, 3.0);
  a.torque_nm = r.real(-2.5, 2.5);
  return a;
}

MitIn makeMit(Rng& r, std::size_t i) {
  MitIn m{};
  m.id = 1u + static_cast<unsigned>(i % 20u);
  m.cmd = {r.realf(-3.0f, 3.0f), r.realf(-20.0f, 20.0f), r.realf(0.0f, 200.0f), r.realf(0.0f, 3.0f),
           r.realf(-5.0f, 5.0f)};
  m.reply = {static_cast<std::uint8_t>(m.id), r.realf(-3.0f, 3.0f), r.realf(-20.0f, 20.0f),
             r.realf(-5.0f, 5.0f)};
  static constexpr mrqp_fw_mit_kind kSpecial[3] = {MRQP_FW_MIT_KIND_ENABLE, MRQP_FW_MIT_KIND_DISABLE,
                                                   MRQP_FW_MIT_KIND_ZERO};
  m.special = kSpecial[i % 3];
  return m;
}

HandIn makeHand(Rng& r, std::size_t i) {
  HandIn h{};
  h.board = static_cast<unsigned>(i % 16u);
  for (std::size_t k = 0; k < 2; ++k) {
    mrqp_fw_hand_cmd& c = h.cmd[k];
    mrqp_fw_hand_fb& f = h.fb[k];
    c.seq = static_cast<std::uint16_t>(i * 977u);
    c.mode = static_cast<std::uint8_t>(1u + i % 3u);
    c.first_joint = static_cast<std::uint8_t>(k == 0 ? 0 : 11);
    c.count = static_cast<std::uint8_t>(k == 0 ? 11 : 9);
    f.cmd_seq_echo = c.seq;
    f.counter = static_cast<std::uint8_t>(2 * i + k);
    f.mode = c.mode;
    f.status = static_cast<std::uint8_t>(MRQP_FW_HAND_STATUS_ENABLED |
                                         ((i % 7u) == 0u ? MRQP_FW_HAND_STATUS_LIMIT : 0u));
    f.first_joint = c.first_joint;
    f.count = c.count;
    for (std::size_t j = 0; j < c.count; ++j) {
      c.joint[j] = {r.realf(-3.0f, 3.0f), r.realf(-30.0f, 30.0f), r.realf(-1.5f, 1.5f)};
      f.joint[j] = {r.realf(-3.0f, 3.0f), r.realf(-30.0f, 30.0f), r.realf(-1.5f, 1.5f)};
    }
  }
  return h;
}

FtIn makeFt(Rng& r, std::size_t i) {
  FtIn t{};
  t.node = 0x30u + static_cast<unsigned>(i & 1u);
  for (std::size_t k = 0; k < 3; ++k) {
    t.classic.wrench[k] = r.real(-500.0, 500.0);
    t.classic.wrench[k + 3] = r.real(-30.0, 30.0);
    t.fd.wrench[k] = r.real(-1500.0, 1500.0);
    t.fd.wrench[k + 3] = r.real(-200.0, 200.0);
  }
  t.classic.seq = t.fd.seq = static_cast<std::uint8_t>(i * 5u);
  t.classic.status = t.fd.status = static_cast<std::uint8_t>((i % 3u) == 0u ? MRQP_FW_FT_STATUS_TARED : 0u);
  t.tare = static_cast<unsigned>(i & 1u) ? MRQP_FW_FT_CMD_TARE : MRQP_FW_FT_CMD_CLEAR_TARE;
  return t;
}

void registerMessages() {
  // ---- CANopen: NMT, SYNC, heartbeat, EMCY ----
  addMessage<NmtIn, 1>(
      "nmt", 1,
      [](Rng& r, std::size_t i) {
        static constexpr mrqp_fw_nmt_cmd kCmd[5] = {MRQP_FW_NMT_START, MRQP_FW_NMT_STOP,
                                                    MRQP_FW_NMT_ENTER_PREOP, MRQP_FW_NMT_RESET_NODE,
                                                    MRQP_FW_NMT_RESET_COMM};
        return NmtIn{kCmd[r.uint(0, 4)], (i % 8u) == 0u ? 0u : nodeOf(i)};
      },
      [](const NmtIn& in, mrqp_fw_frame* f) { return mrqp_fw_nmt_pack(in.cmd, in.node, f); },
      [](const mrqp_fw_frame* f, const NmtIn&) {
        mrqp_fw_nmt_cmd cmd;
        std::uint8_t node;
        const mrqp_fw_err e = mrqp_fw_nmt_unpack(f, &cmd, &node);
        benchmark::DoNotOptimize(cmd);
        benchmark::DoNotOptimize(node);
        return e;
      });
  addMessage<unsigned, 1>(
      "sync", 2,
      [](Rng& r, std::size_t i) { return (i % 8u) == 0u ? 0u : r.uint(1, MRQP_FW_SYNC_COUNTER_MAX); },
      [](const unsigned& counter, mrqp_fw_frame* f) { return mrqp_fw_sync_pack(counter, f); },
      [](const mrqp_fw_frame* f, const unsigned&) {
        std::uint8_t counter;
        const mrqp_fw_err e = mrqp_fw_sync_unpack(f, &counter);
        benchmark::DoNotOptimize(counter);
        return e;
      });
  addMessage<HeartbeatIn, 1>(
      "heartbeat", 3,
      [](Rng& r, std::size_t i) {
        static constexpr mrqp_fw_nmt_state kState[4] = {MRQP_FW_NMT_STATE_BOOTUP, MRQP_FW_NMT_STATE_STOPPED,
                                                        MRQP_FW_NMT_STATE_OPERATIONAL,
                                                        MRQP_FW_NMT_STATE_PRE_OPERATIONAL};
        return HeartbeatIn{nodeOf(i), kState[r.uint(0, 3)]};
      },
      [](const HeartbeatIn& in, mrqp_fw_frame* f) { return mrqp_fw_heartbeat_pack(in.node, in.state, f); },
      [](const mrqp_fw_frame* f, const HeartbeatIn&) {
        std::uint8_t node;
        mrqp_fw_nmt_state state;
        const mrqp_fw_err e = mrqp_fw_heartbeat_unpack(f, &node, &state);
        benchmark::DoNotOptimize(node);
        benchmark::DoNotOptimize(state);
        return e;
      });
  addMessage<EmcyIn, 1>(
      "emcy", 4,
      [](Rng& r, std::size_t i) {
        static constexpr std::uint16_t kCode[6] = {MRQP_FW_EMCY_NO_ERROR,
                                                   MRQP_FW_EMCY_CONTINUOUS_OVER_CURRENT,
                                                   MRQP_FW_EMCY_DC_LINK_UNDER_VOLTAGE,
                                                   MRQP_FW_EMCY_HEARTBEAT_ERROR,
                                                   MRQP_FW_EMCY_FOLLOWING_ERROR,
                                                   MRQP_FW_EMCY_RPDO_TIMEOUT};
        EmcyIn e{};
        e.node = nodeOf(i);
        e.emcy.error_code = kCode[i % 6];
        e.emcy.error_register = static_cast<std::uint8_t>(r.byte() & ~MRQP_FW_ERRREG_RESERVED);
        for (auto& b : e.emcy.manufacturer) {
          b = r.byte();
        }
        return e;
      },
      [](const EmcyIn& in, mrqp_fw_frame* f) { return mrqp_fw_emcy_pack(in.node, &in.emcy, f); },
      [](const mrqp_fw_frame* f, const EmcyIn&) {
        std::uint8_t node;
        mrqp_fw_emcy emcy;
        const mrqp_fw_err e = mrqp_fw_emcy_unpack(f, &node, &emcy);
        benchmark::DoNotOptimize(node);
        benchmark::DoNotOptimize(emcy);
        return e;
      });

  // ---- CANopen SDO: every frame kind of the contract (decode: mrqp_fw_sdo_unpack) ----
  const auto sdo_unpack = [](const mrqp_fw_frame* f, const SdoIn&) {
    return static_cast<mrqp_fw_err>(sdoDecode(f));
  };
  addMessage<SdoIn, 1>(
      "sdo_download_expedited", 10, makeSdo,
      [](const SdoIn& s, mrqp_fw_frame* f) {
        return mrqp_fw_sdo_pack_download_u32(s.node, s.index, s.sub, s.value, s.n, f);
      },
      sdo_unpack);
  addMessage<SdoIn, 1>(
      "sdo_download_resp", 11, makeSdo,
      [](const SdoIn& s, mrqp_fw_frame* f) {
        return mrqp_fw_sdo_pack_download_resp(s.node, s.index, s.sub, f);
      },
      sdo_unpack);
  addMessage<SdoIn, 1>(
      "sdo_upload_req", 12, makeSdo,
      [](const SdoIn& s, mrqp_fw_frame* f) { return mrqp_fw_sdo_pack_upload_req(s.node, s.index, s.sub, f); },
      sdo_unpack);
  addMessage<SdoIn, 1>(
      "sdo_upload_expedited", 13, makeSdo,
      [](const SdoIn& s, mrqp_fw_frame* f) {
        return mrqp_fw_sdo_pack_upload_resp(s.node, s.index, s.sub, s.data.data(), 1u + s.value % 4u, f);
      },
      sdo_unpack);
  addMessage<SdoIn, 1>(
      "sdo_download_init_segmented", 14, makeSdo,
      [](const SdoIn& s, mrqp_fw_frame* f) {
        return mrqp_fw_sdo_pack_download_init_segmented(s.node, s.index, s.sub, 5u + s.value % 200u, f);
      },
      sdo_unpack);
  addMessage<SdoIn, 1>(
      "sdo_upload_resp_segmented", 15, makeSdo,
      [](const SdoIn& s, mrqp_fw_frame* f) {
        return mrqp_fw_sdo_pack_upload_resp_segmented(s.node, s.index, s.sub, 5u + s.value % 200u, f);
      },
      sdo_unpack);
  addMessage<SdoIn, 1>(
      "sdo_segment", 16, makeSdo,
      [](const SdoIn& s, mrqp_fw_frame* f) {
        return mrqp_fw_sdo_pack_segment(s.node, s.from_server, s.toggle, s.data.data(), s.value % 8u, s.last,
                                        f);
      },
      sdo_unpack);
  addMessage<SdoIn, 1>(
      "sdo_download_seg_resp", 17, makeSdo,
      [](const SdoIn& s, mrqp_fw_frame* f) {
        return mrqp_fw_sdo_pack_download_seg_resp(s.node, s.toggle, f);
      },
      sdo_unpack);
  addMessage<SdoIn, 1>(
      "sdo_upload_seg_req", 18, makeSdo,
      [](const SdoIn& s, mrqp_fw_frame* f) { return mrqp_fw_sdo_pack_upload_seg_req(s.node, s.toggle, f); },
      sdo_unpack);
  addMessage<SdoIn, 1>(
      "sdo_abort", 19, makeSdo,
      [](const SdoIn& s, mrqp_fw_frame* f) {
        static constexpr std::uint32_t kAbort[4] = {MRQP_FW_SDO_ABORT_TIMEOUT, MRQP_FW_SDO_ABORT_NO_OBJECT,
                                                    MRQP_FW_SDO_ABORT_TYPE_LENGTH,
                                                    MRQP_FW_SDO_ABORT_STORE_STATE};
        return mrqp_fw_sdo_pack_abort(s.node, s.from_server, s.index, s.sub, kAbort[s.value % 4u], f);
      },
      sdo_unpack);

  // ---- CiA 402 PDOs of the arm drives ----
  addMessage<ArmPdoIn, 1>(
      "rpdo1", 20, makeArm,
      [](const ArmPdoIn& a, mrqp_fw_frame* f) { return mrqp_fw_arm_pack_rpdo1(a.node, &a.rpdo1, f); },
      [](const mrqp_fw_frame* f, const ArmPdoIn& a) {
        mrqp_fw_arm_rpdo1 p;
        const mrqp_fw_err e = mrqp_fw_arm_unpack_rpdo1(f, a.node, &p);
        benchmark::DoNotOptimize(p);
        return e;
      });
  // The master's path: target position (rad) and torque (N m) scaled to increments / per mille.
  addMessage<ArmPdoIn, 1>(
      "rpdo1_si", 21, makeArm,
      [](const ArmPdoIn& a, mrqp_fw_frame* f) {
        return mrqp_fw_arm_pack_rpdo1_si(&kArmScale, a.node, a.rpdo1.controlword, a.position_rad, a.torque_nm,
                                         f);
      },
      [](const mrqp_fw_frame*, const ArmPdoIn&) { return MRQP_FW_OK; }, /*decode=*/false);
  addMessage<ArmPdoIn, 1>(
      "tpdo1", 22, makeArm,
      [](const ArmPdoIn& a, mrqp_fw_frame* f) { return mrqp_fw_arm_pack_tpdo1(a.node, &a.tpdo1, f); },
      [](const mrqp_fw_frame* f, const ArmPdoIn& a) {
        mrqp_fw_arm_tpdo1 p;
        const mrqp_fw_err e = mrqp_fw_arm_unpack_tpdo1(f, a.node, &p);
        benchmark::DoNotOptimize(p);
        return e;
      });
  // The host's path: statusword, position (rad) and torque (N m).
  addMessage<ArmPdoIn, 1>(
      "tpdo1_si", 23, makeArm,
      [](const ArmPdoIn& a, mrqp_fw_frame* f) { return mrqp_fw_arm_pack_tpdo1(a.node, &a.tpdo1, f); },
      [](const mrqp_fw_frame* f, const ArmPdoIn& a) {
        mrqp_fw_arm_tpdo1 p;
        double rad = 0.0;
        double nm = 0.0;
        const mrqp_fw_err e = mrqp_fw_arm_unpack_tpdo1(f, a.node, &p);
        (void)mrqp_fw_arm_position_from_inc(&kArmScale, p.position_actual, &rad);
        (void)mrqp_fw_arm_torque_from_permille(&kArmScale, p.torque_actual, &nm);
        benchmark::DoNotOptimize(p.statusword);
        benchmark::DoNotOptimize(rad);
        benchmark::DoNotOptimize(nm);
        return e;
      },
      /*decode=*/true, /*encode=*/false);
  addMessage<ArmPdoIn, 1>(
      "tpdo2", 24, makeArm,
      [](const ArmPdoIn& a, mrqp_fw_frame* f) { return mrqp_fw_arm_pack_tpdo2(a.node, &a.tpdo2, f); },
      [](const mrqp_fw_frame* f, const ArmPdoIn& a) {
        mrqp_fw_arm_tpdo2 p;
        const mrqp_fw_err e = mrqp_fw_arm_unpack_tpdo2(f, a.node, &p);
        benchmark::DoNotOptimize(p);
        return e;
      });
  addMessage<ArmPdoIn, 1>(
      "tpdo2_si", 25, makeArm,
      [](const ArmPdoIn& a, mrqp_fw_frame* f) { return mrqp_fw_arm_pack_tpdo2(a.node, &a.tpdo2, f); },
      [](const mrqp_fw_frame* f, const ArmPdoIn& a) {
        mrqp_fw_arm_tpdo2 p;
        double rad_s = 0.0;
        const mrqp_fw_err e = mrqp_fw_arm_unpack_tpdo2(f, a.node, &p);
        (void)mrqp_fw_arm_velocity_from_inc(&kArmScale, p.velocity_actual, &rad_s);
        benchmark::DoNotOptimize(rad_s);
        benchmark::DoNotOptimize(p.error_code);
        benchmark::DoNotOptimize(p.mode_display);
        return e;
      },
      /*decode=*/true, /*encode=*/false);

  // ---- hand: MIT-mode frames ----
  addMessage<MitIn, 1>(
      "mit_command", 30, makeMit,
      [](const MitIn& m, mrqp_fw_frame* f) { return mrqp_fw_mit_pack_cmd(&kMitRanges, m.id, &m.cmd, f); },
      [](const mrqp_fw_frame* f, const MitIn&) {
        std::uint8_t id;
        mrqp_fw_mit_cmd c;
        const mrqp_fw_err e = mrqp_fw_mit_unpack_cmd(&kMitRanges, f, &id, &c);
        benchmark::DoNotOptimize(id);
        benchmark::DoNotOptimize(c);
        return e;
      });
  addMessage<MitIn, 1>(
      "mit_special", 31, makeMit,
      [](const MitIn& m, mrqp_fw_frame* f) { return mrqp_fw_mit_pack_special(m.id, m.special, f); },
      [](const mrqp_fw_frame* f, const MitIn&) {
        const mrqp_fw_mit_kind k = mrqp_fw_mit_classify(f);
        benchmark::DoNotOptimize(k);
        return k == MRQP_FW_MIT_KIND_INVALID || k == MRQP_FW_MIT_KIND_COMMAND ? MRQP_FW_ERR_FORMAT
                                                                              : MRQP_FW_OK;
      });
  addMessage<MitIn, 1>(
      "mit_reply", 32, makeMit,
      [](const MitIn& m, mrqp_fw_frame* f) { return mrqp_fw_mit_pack_reply(&kMitRanges, &m.reply, f); },
      [](const mrqp_fw_frame* f, const MitIn&) {
        mrqp_fw_mit_reply r;
        const mrqp_fw_err e = mrqp_fw_mit_unpack_reply(&kMitRanges, f, &r);
        benchmark::DoNotOptimize(r);
        return e;
      });

  // ---- hand: CAN FD board frames, 20 joints = 2 frames (11 + 9 joints), sequence and CRC ----
  addMessage<HandIn, 2>(
      "hand_fd_command_20j", 40, makeHand,
      [](const HandIn& h, mrqp_fw_frame* f) {
        return mrqp_fw_hand_pack_cmd(&kHandScale, h.board, &h.cmd[0], &f[0], nullptr) |
               mrqp_fw_hand_pack_cmd(&kHandScale, h.board, &h.cmd[1], &f[1], nullptr);
      },
      [](const mrqp_fw_frame* f, const HandIn& h) {
        mrqp_fw_hand_cmd c;
        mrqp_fw_err e = mrqp_fw_hand_unpack_cmd(&kHandScale, &f[0], h.board, &c);
        benchmark::DoNotOptimize(c);
        if (e == MRQP_FW_OK) {
          e = mrqp_fw_hand_unpack_cmd(&kHandScale, &f[1], h.board, &c);
          benchmark::DoNotOptimize(c);
        }
        return e;
      });
  addMessage<HandIn, 2>(
      "hand_fd_feedback_20j", 41, makeHand,
      [](const HandIn& h, mrqp_fw_frame* f) {
        return mrqp_fw_hand_pack_fb(&kHandScale, h.board, &h.fb[0], &f[0], nullptr) |
               mrqp_fw_hand_pack_fb(&kHandScale, h.board, &h.fb[1], &f[1], nullptr);
      },
      [](const mrqp_fw_frame* f, const HandIn& h) {
        mrqp_fw_hand_fb fb;
        mrqp_fw_err e = mrqp_fw_hand_unpack_fb(&kHandScale, &f[0], h.board, &fb);
        benchmark::DoNotOptimize(fb);
        if (e == MRQP_FW_OK) {
          e = mrqp_fw_hand_unpack_fb(&kHandScale, &f[1], h.board, &fb);
          benchmark::DoNotOptimize(fb);
        }
        return e;
      });

  // ---- wrist force/torque sensor ----
  addMessage<FtIn, 2>(
      "ft_classic_pair", 50, makeFt,
      [](const FtIn& t, mrqp_fw_frame* f) {
        return mrqp_fw_ft_pack_classic(&kFtClassic, t.node, &t.classic, &f[0], &f[1]);
      },
      [](const mrqp_fw_frame* f, const FtIn& t) {
        mrqp_fw_ft_sample s;
        const mrqp_fw_err e = mrqp_fw_ft_unpack_classic(&kFtClassic, &f[0], &f[1], t.node, &s);
        benchmark::DoNotOptimize(s);
        return e;
      });
  addMessage<FtIn, 1>(
      "ft_fd", 51, makeFt,
      [](const FtIn& t, mrqp_fw_frame* f) { return mrqp_fw_ft_pack_fd(&kFtFd, t.node, &t.fd, f); },
      [](const mrqp_fw_frame* f, const FtIn& t) {
        mrqp_fw_ft_sample s;
        const mrqp_fw_err e = mrqp_fw_ft_unpack_fd(&kFtFd, f, t.node, &s);
        benchmark::DoNotOptimize(s);
        return e;
      });
  addMessage<FtIn, 1>(
      "ft_tare", 52, makeFt,
      [](const FtIn& t, mrqp_fw_frame* f) { return mrqp_fw_ft_pack_tare(t.node, t.tare, f); },
      [](const mrqp_fw_frame* f, const FtIn& t) {
        std::uint8_t cmd;
        const mrqp_fw_err e = mrqp_fw_ft_unpack_tare(f, t.node, &cmd);
        benchmark::DoNotOptimize(cmd);
        return e;
      });
}

// ---- one cycle of the device set: 7 arm drives, 20 MIT motors, 2 force/torque sensors ------------

constexpr std::size_t kArmDrives = 7;
constexpr std::size_t kMitMotors = 20;
constexpr std::size_t kFtSensors = 2;
/// Host frames per cycle: sent 7 RPDO1 + 1 SYNC + 20 MIT commands, received 7 TPDO1 + 7 TPDO2 +
/// 20 MIT replies + 2 x 2 force/torque halves.
constexpr int kCycleFrames =
    static_cast<int>(kArmDrives + 1 + kMitMotors + 2 * kArmDrives + kMitMotors + 2 * kFtSensors);

/// The host codec work of one cycle, no driver logic.
void bmCycleCodec(benchmark::State& state) {
  struct Ring {
    std::array<double, kArmDrives> position;
    std::array<mrqp_fw_mit_cmd, kMitMotors> mit;
    std::array<mrqp_fw_frame, kArmDrives> tpdo1;
    std::array<mrqp_fw_frame, kArmDrives> tpdo2;
    std::array<mrqp_fw_frame, kMitMotors> reply;
    std::array<std::array<mrqp_fw_frame, 2>, kFtSensors> ft;
  };
  constexpr std::size_t kCycles = 64;  // x 66 frames: 4224 distinct frames
  std::vector<Ring> ring(kCycles);
  Rng rng(60);
  for (std::size_t i = 0; i < kCycles; ++i) {
    Ring& c = ring[i];
    for (std::size_t d = 0; d < kArmDrives; ++d) {
      const ArmPdoIn a = makeArm(rng, d);
      c.position[d] = a.position_rad;
      (void)mrqp_fw_arm_pack_tpdo1(static_cast<unsigned>(d + 1), &a.tpdo1, &c.tpdo1[d]);
      (void)mrqp_fw_arm_pack_tpdo2(static_cast<unsigned>(d + 1), &a.tpdo2, &c.tpdo2[d]);
    }
    for (std::size_t m = 0; m < kMitMotors; ++m) {
      const MitIn in = makeMit(rng, m);
      c.mit[m] = in.cmd;
      (void)mrqp_fw_mit_pack_reply(&kMitRanges, &in.reply, &c.reply[m]);
    }
    for (std::size_t s = 0; s < kFtSensors; ++s) {
      const FtIn t = makeFt(rng, s);
      (void)mrqp_fw_ft_pack_classic(&kFtClassic, t.node, &t.classic, &c.ft[s][0], &c.ft[s][1]);
    }
  }
  std::uint32_t failed = 0;
  std::size_t i = 0;
  mrqp_fw_frame out{};
  std::uint8_t sync_counter = 1;
  for (auto _ : state) {
    const Ring& c = ring[i];
    for (std::size_t d = 0; d < kArmDrives; ++d) {
      failed |= packErr(mrqp_fw_arm_pack_rpdo1_si(&kArmScale, static_cast<unsigned>(d + 1),
                                                  MRQP_FW_CW_ENABLE_OPERATION_CMD, c.position[d], 0.0, &out));
      benchmark::DoNotOptimize(out);
    }
    failed |= packErr(mrqp_fw_sync_pack(sync_counter, &out));
    benchmark::DoNotOptimize(out);
    sync_counter = mrqp_fw_sync_counter_next(sync_counter, MRQP_FW_SYNC_COUNTER_MAX);
    for (std::size_t m = 0; m < kMitMotors; ++m) {
      failed |= packErr(mrqp_fw_mit_pack_cmd(&kMitRanges, static_cast<unsigned>(m + 1), &c.mit[m], &out));
      benchmark::DoNotOptimize(out);
    }
    for (std::size_t d = 0; d < kArmDrives; ++d) {
      mrqp_fw_arm_tpdo1 p1;
      mrqp_fw_arm_tpdo2 p2;
      double v[3] = {0.0, 0.0, 0.0};
      failed |= unpackErr(mrqp_fw_arm_unpack_tpdo1(&c.tpdo1[d], static_cast<unsigned>(d + 1), &p1));
      failed |= unpackErr(mrqp_fw_arm_unpack_tpdo2(&c.tpdo2[d], static_cast<unsigned>(d + 1), &p2));
      (void)mrqp_fw_arm_position_from_inc(&kArmScale, p1.position_actual, &v[0]);
      (void)mrqp_fw_arm_torque_from_permille(&kArmScale, p1.torque_actual, &v[1]);
      (void)mrqp_fw_arm_velocity_from_inc(&kArmScale, p2.velocity_actual, &v[2]);
      benchmark::DoNotOptimize(v);
      benchmark::DoNotOptimize(p1.statusword);
      benchmark::DoNotOptimize(p2.error_code);
    }
    for (std::size_t m = 0; m < kMitMotors; ++m) {
      mrqp_fw_mit_reply r;
      failed |= unpackErr(mrqp_fw_mit_unpack_reply(&kMitRanges, &c.reply[m], &r));
      benchmark::DoNotOptimize(r);
    }
    for (std::size_t s = 0; s < kFtSensors; ++s) {
      mrqp_fw_ft_sample smp;
      failed |= unpackErr(mrqp_fw_ft_unpack_classic(&kFtClassic, &c.ft[s][0], &c.ft[s][1],
                                                    0x30u + static_cast<unsigned>(s & 1u), &smp));
      benchmark::DoNotOptimize(smp);
    }
    i = (i + 1) % kCycles;
  }
  benchmark::DoNotOptimize(failed);
  if (failed != 0u) {
    state.SkipWithError("a frame of the cycle failed");
    return;
  }
  report(state, kCycleFrames);
}

using namespace mrqp::drivers;

/// A Bus in front of a SimNode: forwards everything while live; records the frames received in
/// one cycle; in replay, discards what is sent and returns the recorded frames once per cycle
/// (with the timestamps shifted to the cycle, and a few payload bytes advanced so that the
/// drivers decode changing values and the sensors' sequence numbers keep counting).
class ReplayBus final : public Bus {
 public:
  explicit ReplayBus(SimNode& node, std::vector<std::uint8_t> ft_nodes)
      : node_(node), ft_nodes_(std::move(ft_nodes)) {}

  void startRecording(TimeNs cycle) noexcept {
    recording_ = true;
    count_ = 0;
    recorded_at_ = cycle;
  }
  void startReplay() noexcept {
    recording_ = false;
    replay_ = true;
  }
  /// Prepares the replay of cycle k (>= 1 after the recorded one) at time now.
  void beginCycle(TimeNs now, std::uint32_t k) noexcept {
    now_ = now;
    k_ = k;
    pos_ = 0;
  }
  std::size_t recorded() const noexcept { return count_; }
  std::uint64_t sent() const noexcept { return sent_; }

  SendResult send(const mrqp_fw_frame& frame) noexcept override {
    if (!replay_) {
      return node_.send(frame);
    }
    ++sent_;
    sink_ ^= frame.id ^ frame.data[0] ^ frame.data[7];
    benchmark::DoNotOptimize(sink_);
    return SendResult::Ok;
  }
  ReceiveResult receive(RxFrame& out) noexcept override {
    if (!replay_) {
      const ReceiveResult r = node_.receive(out);
      if (recording_ && r == ReceiveResult::Frame && count_ < frames_.size()) {
        frames_[count_++] = out;
      }
      return r;
    }
    if (pos_ == count_) {
      return ReceiveResult::Empty;
    }
    out = frames_[pos_++];
    out.timestamp = now_ + (out.timestamp - recorded_at_);
    patch(out.frame);
    return ReceiveResult::Frame;
  }
  BusStatus status() const noexcept override { return node_.status(); }
  bool fdEnabled() const noexcept override { return node_.fdEnabled(); }
  const char* name() const noexcept override { return node_.name(); }

 private:
  void patch(mrqp_fw_frame& f) const noexcept {
    const std::uint8_t k = static_cast<std::uint8_t>(k_);
    if (f.id == MRQP_FW_MIT_MASTER_ID) {
      f.data[2] = static_cast<std::uint8_t>(f.data[2] + k);  // MIT reply: position low byte
      return;
    }
    const std::uint32_t node = f.id & 0x7Fu;
    const std::uint32_t base = f.id & ~0x7Fu;
    const bool ft = std::find(ft_nodes_.begin(), ft_nodes_.end(), node) != ft_nodes_.end();
    if (ft && (base == MRQP_FW_COB_TPDO1_BASE || base == MRQP_FW_COB_TPDO2_BASE)) {
      f.data[0] = static_cast<std::uint8_t>(f.data[0] + k);  // fx / mx low byte
      f.data[6] = static_cast<std::uint8_t>(f.data[6] + k);  // sequence
    } else if (base == MRQP_FW_COB_TPDO1_BASE) {
      f.data[2] = static_cast<std::uint8_t>(f.data[2] + k);  // position actual, low byte
    } else if (base == MRQP_FW_COB_TPDO2_BASE) {
      f.data[0] = static_cast<std::uint8_t>(f.data[0] + k);  // velocity actual, low byte
    }
  }

  SimNode& node_;
  std::vector<std::uint8_t> ft_nodes_;
  std::array<RxFrame, 128> frames_{};
  std::size_t count_ = 0;
  std::size_t pos_ = 0;
  bool recording_ = false;
  bool replay_ = false;
  TimeNs recorded_at_ = 0;
  TimeNs now_ = 0;
  std::uint32_t k_ = 0;
  std::uint64_t sent_ = 0;
  std::uint32_t sink_ = 0;
};

/// The device set on two simulated buses with the fake devices of tests/drivers, booted and
/// enabled: arm bus (7 CiA 402 drives, 2 classic force/torque sensors), MIT bus (20 motors).
struct Robot {
  static constexpr TimeNs kPeriod = milliseconds(10);

  Robot() {
    SimNodeConfig mc;
    mc.name = "master";
    mc.rx_queue = 1024;
    arm_master = arm_bus.addNode(mc);
    mit_master = mit_bus.addNode(mc);
    arm_proxy = std::make_unique<ReplayBus>(*arm_master, std::vector<std::uint8_t>{0x30, 0x31});
    mit_proxy = std::make_unique<ReplayBus>(*mit_master, std::vector<std::uint8_t>{});
    arm_router = std::make_unique<BusRouter>(*arm_proxy);
    mit_router = std::make_unique<BusRouter>(*mit_proxy);

    ArmConfig ac;
    ac.cycle_period = kPeriod;
    ac.producer_heartbeat_ms = 0;
    for (std::size_t d = 0; d < kArmDrives; ++d) {
      drvtest::FakeDriveOptions o;
      o.node = static_cast<std::uint8_t>(d + 1);
      o.initial_position = static_cast<std::int32_t>(1000 * d);
      drives.push_back(std::make_unique<drvtest::FakeCia402Drive>(*arm_bus.addNode(SimNodeConfig{}), o));
      ArmDriveConfig dc;
      dc.node = o.node;
      ac.drives.push_back(dc);
    }
    FtConfig fc;
    for (std::size_t s = 0; s < kFtSensors; ++s) {
      const std::uint8_t node = static_cast<std::uint8_t>(0x30 + s);
      sensors.push_back(
          std::make_unique<drvtest::FakeFtSensor>(*arm_bus.addNode(SimNodeConfig{}), node, false));
      sensors.back()->setWrench({10.0 + static_cast<double>(s), -4.0, 25.0, 0.5, -0.25, 0.125});
      FtSensorConfig sc;
      sc.node = node;
      fc.sensors.push_back(sc);
    }
    mit_fake = std::make_unique<drvtest::FakeMitMotors>(*mit_bus.addNode(SimNodeConfig{}));
    MitHandConfig hc;
    for (std::size_t m = 0; m < kMitMotors; ++m) {
      const std::uint8_t id = static_cast<std::uint8_t>(m + 1);
      mit_fake->add(id);
      MitMotorConfig mm;
      mm.motor_id = id;
      hc.motors.push_back(mm);
    }
    arm = ArmDriver::create({arm_router.get()}, ac, &error);
    if (arm) {
      ft = FtSensorDriver::create({arm_router.get()}, fc, &error);
    }
    if (ft) {
      mit = MitHandDriver::create({mit_router.get()}, hc, &error);
    }
    // Smooth setpoints (one period per 64 cycles): the fake motors' torque, kp (p_set - p), stays
    // within the reply's range.
    for (std::size_t i = 0; i < kRing; ++i) {
      const double phase = 2.0 * M_PI * static_cast<double>(i) / static_cast<double>(kRing);
      position[i] = 0.5 * std::sin(phase);
      mit_cmd[i] = {static_cast<float>(0.3 * std::sin(phase)), static_cast<float>(0.3 * std::cos(phase)),
                    20.0f, 0.5f, static_cast<float>(0.1 * std::cos(phase))};
    }
  }

  /// One control cycle at t, then t += period (the order of tests/drivers/arm_rig.hpp: the NMT
  /// reset goes out at the time of start(), before the drives' power-up boot-up messages, which
  /// the arm driver would otherwise take as the answer to it); `sim` advances the simulated buses
  /// first, else the replay buses serve the recorded cycle. Returns the fault flags of the cycle,
  /// and bit 31 if a setpoint was not accepted as it is.
  std::uint32_t cycle(bool sim) noexcept {
    ++k;
    if (sim) {
      arm_bus.advanceTo(t);
      mit_bus.advanceTo(t);
    } else {
      arm_proxy->beginCycle(t, replay_k);
      mit_proxy->beginCycle(t, replay_k);
      ++replay_k;
    }
    arm_router->poll(t);
    mit_router->poll(t);
    std::uint32_t flags = arm->update(t).flags | ft->update(t).flags | mit->update(t).flags;
    if (arm->allEnabled()) {
      for (std::size_t d = 0; d < kArmDrives; ++d) {
        flags |= arm->setPosition(d, position[(k + d) & kMask]) == SetpointResult::Ok ? 0u : 0x80000000u;
      }
    }
    if (mit->allOn()) {
      for (std::size_t m = 0; m < kMitMotors; ++m) {
        flags |= mit->setCommand(m, mit_cmd[(k + m) & kMask]) == SetpointResult::Ok ? 0u : 0x80000000u;
      }
    }
    arm->transmit(t);
    ft->transmit(t);
    mit->transmit(t);
    t += kPeriod;
    return flags;
  }

  /// Boots and enables everything over the simulated buses. Empty string on success.
  std::string boot() {
    if (!arm || !ft || !mit) {
      return "driver creation failed: " + error;
    }
    arm->start(t);
    int n = 0;
    for (; n < 1000 && arm->phase() != ArmPhase::Running; ++n) {
      if (arm->phase() == ArmPhase::Failed) {
        return "arm boot failed after " + std::to_string(n) +
               " cycles: " + describeFaults(arm->faults(), "drive");
      }
      (void)cycle(true);
    }
    if (arm->phase() != ArmPhase::Running) {
      return "arm boot timed out";
    }
    ft->start(t);
    arm->requestEnable(t);
    mit->requestEnable(t);
    bool ready = false;
    for (n = 0; n < 1000 && !ready; ++n) {
      (void)cycle(true);
      ready = arm->allEnabled() && mit->allOn() && ft->sensor(0).valid && ft->sensor(1).valid;
    }
    if (!ready) {
      return "enable timed out";
    }
    // Steady state: every cycle clean.
    std::uint32_t flags = 0;
    for (n = 0; n < 50; ++n) {
      flags |= cycle(true);
    }
    if (flags != 0u) {
      return "faults after enable: flags 0x" + hex(flags);
    }
    return {};
  }

  /// Records one steady-state cycle and switches to replay. Empty string on success.
  std::string record() {
    arm_proxy->startRecording(t);
    mit_proxy->startRecording(t);
    const std::uint32_t flags = cycle(true);
    arm_proxy->startReplay();
    mit_proxy->startReplay();
    replay_k = 1;
    const std::size_t arm_expected = 2 * kArmDrives + 2 * kFtSensors;
    if (flags != 0u || arm_proxy->recorded() != arm_expected || mit_proxy->recorded() != kMitMotors) {
      return "recorded cycle: flags 0x" + hex(flags) + ", " + std::to_string(arm_proxy->recorded()) +
             " arm-bus frames (expected " + std::to_string(arm_expected) + "), " +
             std::to_string(mit_proxy->recorded()) + " MIT replies (expected " + std::to_string(kMitMotors) +
             ")";
    }
    return {};
  }

  static std::string hex(std::uint32_t v) {
    char b[16];
    std::snprintf(b, sizeof b, "%08X", v);
    return b;
  }

  SimBus arm_bus;
  SimBus mit_bus;
  SimNode* arm_master = nullptr;
  SimNode* mit_master = nullptr;
  std::unique_ptr<ReplayBus> arm_proxy;
  std::unique_ptr<ReplayBus> mit_proxy;
  std::unique_ptr<BusRouter> arm_router;
  std::unique_ptr<BusRouter> mit_router;
  std::vector<std::unique_ptr<drvtest::FakeCia402Drive>> drives;
  std::vector<std::unique_ptr<drvtest::FakeFtSensor>> sensors;
  std::unique_ptr<drvtest::FakeMitMotors> mit_fake;
  std::unique_ptr<ArmDriver> arm;
  std::unique_ptr<FtSensorDriver> ft;
  std::unique_ptr<MitHandDriver> mit;
  std::string error;
  std::array<double, kRing> position{};
  std::array<mrqp_fw_mit_cmd, kRing> mit_cmd{};
  TimeNs t = 0;
  std::size_t k = 0;
  std::uint32_t replay_k = 0;
};

void bmCycleDrivers(benchmark::State& state, bool sim) {
  auto robot = std::make_unique<Robot>();
  std::string err = robot->boot();
  if (err.empty() && !sim) {
    err = robot->record();
  }
  if (!err.empty()) {
    state.SkipWithError(err.c_str());
    return;
  }
  std::uint32_t flags = 0;
  for (auto _ : state) {
    flags |= robot->cycle(sim);
  }
  const bool ok = flags == 0u && robot->arm->allEnabled() && robot->mit->allOn() &&
                  robot->ft->sensor(0).fresh && robot->ft->sensor(1).fresh;
  if (!ok) {
    state.SkipWithError(("faults during the timed cycles: flags 0x" + Robot::hex(flags)).c_str());
    return;
  }
  report(state, kCycleFrames);
}

}  // namespace

static int unwrappedMain(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) {
    return 2;
  }
  benchmark::AddCustomContext("mrqp_compiler", __VERSION__);
  benchmark::AddCustomContext("mrqp_build_type", MRQP_TOOLS_BUILD_TYPE);
#ifdef NDEBUG
  benchmark::AddCustomContext("mrqp_ndebug", "yes");
#else
  benchmark::AddCustomContext("mrqp_ndebug", "no (assertions on: timings are not representative)");
#endif

  registerMessages();
  withMax(benchmark::RegisterBenchmark("BM_cycle/codec", bmCycleCodec))->Unit(benchmark::kMicrosecond);
  withMax(benchmark::RegisterBenchmark("BM_cycle/drivers_host", [](benchmark::State& s) {
    bmCycleDrivers(s, false);
  }))->Unit(benchmark::kMicrosecond);
  withMax(benchmark::RegisterBenchmark("BM_cycle/drivers_sim_bus", [](benchmark::State& s) {
    bmCycleDrivers(s, true);
  }))->Unit(benchmark::kMicrosecond);

  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}

// Any exception becomes one error line and exit status 1 (docs/robustness.md).
int main(int argc, char** argv) {
  try {
    return unwrappedMain(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: %s\n", "bench_codec", e.what());
  } catch (...) {
    std::fprintf(stderr, "%s: unknown error\n", "bench_codec");
  }
  return 1;
}
