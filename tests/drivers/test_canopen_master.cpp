// The CANopen master's protocol units (drivers/canopen) on their own, against CiA 301 frames
// worked out by hand (NMT 000#<cs><node>, SDO 600+node / 580+node, SYNC 080#<counter>,
// heartbeat 700+node#<state>): NmtBoot, SdoWriteSequence, HeartbeatConsumer, SyncProducer,
// HeartbeatProducer.
#include <catch2/catch.hpp>

#include <mrqp/firmware_if/nmt.h>
#include <mrqp/firmware_if/sdo.h>
#include <mrqp/drivers/canopen/heartbeat_consumer.hpp>
#include <mrqp/drivers/canopen/heartbeat_producer.hpp>
#include <mrqp/drivers/canopen/nmt_boot.hpp>
#include <mrqp/drivers/canopen/sdo_write_sequence.hpp>
#include <mrqp/drivers/canopen/sync_producer.hpp>

#include <string>
#include <vector>

#include "sim_trace.hpp"

using namespace mrqp::drivers;
using drvtest::frameStr;

TEST_CASE("drivers: canopen: NmtBoot commands and the boot-up wait", "[drivers][canopen]") {
  NmtBoot n;
  mrqp_fw_frame f{};
  n.init(5, NmtReset::Node, milliseconds(100));
  CHECK_FALSE(n.waiting());
  CHECK_FALSE(n.onBootUp(0));  // not awaited
  n.begin(milliseconds(10), &f);
  CHECK(frameStr(f) == "000#8105");
  CHECK(n.waiting());
  CHECK(n.commanded() == milliseconds(10));
  CHECK_FALSE(n.process(milliseconds(110)));
  CHECK(n.process(milliseconds(110) + 1));
  // Not an answer: the reset has not been handed to the bus yet.
  CHECK_FALSE(n.onBootUp(milliseconds(10)));
  n.sent(milliseconds(11));
  CHECK_FALSE(n.onBootUp(milliseconds(11) - 1));  // received before the reset was sent
  CHECK(n.waiting());
  CHECK(n.onBootUp(milliseconds(12)));
  CHECK(n.booted());
  CHECK_FALSE(n.process(seconds(1)));
  n.startRemote(milliseconds(20), &f);
  CHECK(frameStr(f) == "000#0105");
  CHECK(n.commanded() == milliseconds(20));

  n.init(7, NmtReset::Communication, milliseconds(100));
  n.begin(0, &f);
  CHECK(frameStr(f) == "000#8207");
  CHECK_FALSE(n.booted());
  // With TX echoes: a boot-up counts only after the reset's own echo, whatever its time.
  n.setEcho(true);
  n.sent(0);
  CHECK_FALSE(n.onBootUp(milliseconds(3)));
  mrqp_fw_frame other{};
  (void)mrqp_fw_nmt_pack(MRQP_FW_NMT_RESET_COMM, 8, &other);
  CHECK_FALSE(n.onOwnCommand(other));  // another node's reset
  (void)mrqp_fw_nmt_pack(MRQP_FW_NMT_START, 7, &other);
  CHECK_FALSE(n.onOwnCommand(other));  // not the boot command
  CHECK(n.onOwnCommand(f));
  CHECK(n.onBootUp(milliseconds(3)));
  n.setEcho(false);
  n.init(7, NmtReset::None, milliseconds(100));
  n.begin(0, &f);
  CHECK(frameStr(f) == "000#8007");
  CHECK(n.booted());  // no reset, no wait
  CHECK_FALSE(n.process(seconds(10)));
}

TEST_CASE("drivers: canopen: SdoWriteSequence, one write in flight, abort and timeout",
          "[drivers][canopen]") {
  SdoWriteSequence s;
  s.init(3, {{0x1017, 0, 2, 100}, {0x6060, 0, 1, 8}, {0x1006, 0, 4, 1000}}, milliseconds(100));
  mrqp_fw_frame out{};
  mrqp_fw_frame resp{};
  CHECK(s.process(0, false, &out) == SdoWriteSequence::Step::Idle);  // not asked to start
  REQUIRE(s.process(0, true, &out) == SdoWriteSequence::Step::Send);
  // Expedited download of 2 bytes: cs 0x2B, index LE, sub, data LE.
  CHECK(frameStr(out) == "603#2B17100064000000");
  CHECK(s.busy());
  CHECK(s.process(milliseconds(1), true, &out) == SdoWriteSequence::Step::Idle);  // one at a time
  REQUIRE(!mrqp_fw_pack_failed(mrqp_fw_sdo_pack_download_resp(3, 0x1017, 0, &resp)));
  CHECK(s.onFrame(resp, &out) == SdoWriteSequence::Step::Done);
  CHECK(s.onFrame(resp, &out) == SdoWriteSequence::Step::Unexpected);  // nothing in flight
  REQUIRE(s.process(milliseconds(2), true, &out) == SdoWriteSequence::Step::Send);
  CHECK(frameStr(out) == "603#2F60600008000000");
  // The server aborts: the write stays current, its code is kept.
  REQUIRE(!mrqp_fw_pack_failed(mrqp_fw_sdo_pack_abort(3, 1, 0x6060, 0, 0x06090030u, &resp)));
  CHECK(s.onFrame(resp, &out) == SdoWriteSequence::Step::Failed);
  CHECK(s.abortCode() == 0x06090030u);
  CHECK(s.current().index == 0x6060);
  CHECK_FALSE(s.done());

  // Restart, and a server that stays silent: after the SDO timeout from the time the request
  // left, the client aborts (0x05040000) and the frame to send says so.
  s.restart();
  REQUIRE(s.process(milliseconds(10), true, &out) == SdoWriteSequence::Step::Send);
  s.sent(milliseconds(15));  // kept back by a full queue, left 5 ms later
  CHECK(s.process(milliseconds(115), false, &out) == SdoWriteSequence::Step::Idle);
  CHECK(s.process(milliseconds(115) + 1, false, &out) == SdoWriteSequence::Step::FailedSend);
  CHECK(frameStr(out) == "603#8017100000000405");
  CHECK(s.abortCode() == 0x05040000u);
  CHECK(s.position() == 0u);
}

TEST_CASE("drivers: canopen: heartbeat consumer and producer, SYNC producer", "[drivers][canopen]") {
  HeartbeatConsumer c;
  c.init(true, milliseconds(250));
  CHECK_FALSE(c.process(seconds(10)));  // not monitored before the first heartbeat
  CHECK(c.state() == 0xFF);
  c.onHeartbeat(MRQP_FW_NMT_STATE_PRE_OPERATIONAL, milliseconds(100));
  CHECK(c.monitoring());
  CHECK(c.state() == 0x7F);
  CHECK_FALSE(c.process(milliseconds(350)));
  CHECK(c.process(milliseconds(350) + 1));
  c.restart();
  CHECK_FALSE(c.process(seconds(10)));
  HeartbeatConsumer silent;
  silent.init(false, milliseconds(250));  // the node was not asked to produce heartbeats
  silent.onHeartbeat(MRQP_FW_NMT_STATE_OPERATIONAL, 0);
  CHECK_FALSE(silent.process(seconds(10)));

  SyncProducer sync;
  sync.init(3);
  std::vector<std::string> frames;
  mrqp_fw_frame f{};
  for (int k = 0; k < 5; ++k) {
    sync.process(0, &f);
    frames.push_back(frameStr(f));
  }
  CHECK(frames == std::vector<std::string>{"080#01", "080#02", "080#03", "080#01", "080#02"});
  sync.restart();
  sync.process(0, &f);
  CHECK(frameStr(f) == "080#01");
  sync.init(0);
  sync.process(0, &f);
  CHECK(frameStr(f) == "080#");

  HeartbeatProducer hb;
  hb.init(0x7F, 20);
  hb.restart(milliseconds(3));
  std::vector<TimeNs> sent;
  for (TimeNs t = milliseconds(3); t < milliseconds(70); t += milliseconds(1)) {
    if (hb.process(t, &f)) {
      sent.push_back(t);
      CHECK(frameStr(f) == "77F#05");
    }
  }
  CHECK(sent == std::vector<TimeNs>{milliseconds(3), milliseconds(23), milliseconds(43), milliseconds(63)});
  // A late cycle does not accumulate heartbeats: the next one is a whole period later.
  hb.restart(0);
  CHECK(hb.process(milliseconds(55), &f));
  CHECK_FALSE(hb.process(milliseconds(59), &f));
  CHECK(hb.process(milliseconds(60), &f));
  HeartbeatProducer none;
  none.init(0, 20);
  CHECK_FALSE(none.process(seconds(1), &f));
}
