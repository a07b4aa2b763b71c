// The in-process bus against hand-computed facts of ISO 11898-1: frame lengths in bits,
// arbitration order, acknowledgement, fault confinement counters and states, bus-off recovery.
#include <catch2/catch.hpp>

#include <mrqp/drivers/sim_bus.hpp>

#include "sim_trace.hpp"

using namespace mrqp::drivers;
using drvtest::makeFrame;
using drvtest::WireLog;

namespace {

mrqp_fw_frame classic(std::uint32_t id, unsigned len) {
  mrqp_fw_frame f{};
  f.id = id;
  f.len = static_cast<std::uint8_t>(len);
  for (unsigned i = 0; i < len; ++i) {
    f.data[i] = static_cast<std::uint8_t>(0x11 * (i + 1));
  }
  return f;
}

mrqp_fw_frame fd(std::uint32_t id, unsigned len, bool brs = true) {
  mrqp_fw_frame f = classic(id, 0);
  f.len = static_cast<std::uint8_t>(len);
  f.flags = static_cast<std::uint8_t>(MRQP_FW_FRAME_FD | (brs ? MRQP_FW_FRAME_BRS : 0u));
  return f;
}

struct Pair {
  explicit Pair(SimBusConfig c = SimBusConfig{}) : bus(c) {
    SimNodeConfig a;
    a.name = "a";
    a.fd = true;
    SimNodeConfig b;
    b.name = "b";
    b.fd = true;
    na = bus.addNode(a);
    nb = bus.addNode(b);
    bus.setTap(&log);
  }
  SimBus bus;
  SimNode* na;
  SimNode* nb;
  WireLog log;
};

}  // namespace

TEST_CASE("drivers: classic frame durations equal the hand-computed bit counts", "[drivers][simbus]") {
  // 47 + 8n bits; worst-case stuffing adds floor((34 + 8n - 1) / 4) stuff bits.
  const unsigned plain[9] = {47, 55, 63, 71, 79, 87, 95, 103, 111};
  const unsigned worst[9] = {55, 65, 75, 85, 95, 105, 115, 125, 135};
  for (bool stuffing : {false, true}) {
    for (std::uint32_t bps : {1000000u, 500000u, 250000u}) {
      SimBusConfig c;
      c.nominal_bps = bps;
      c.worst_case_stuffing = stuffing;
      Pair p(c);
      for (unsigned n = 0; n <= 8; ++n) {
        p.log.clear();
        REQUIRE(p.na->send(classic(0x123, n)) == SendResult::Ok);
        p.bus.advance(seconds(1));
        REQUIRE(p.log.events.size() == 1);
        const WireEvent& e = p.log.events[0];
        CHECK(e.outcome == WireOutcome::Delivered);
        const unsigned bits = stuffing ? worst[n] : plain[n];
        CHECK(e.bits.nominal_bits == bits);
        CHECK(e.end - e.start == static_cast<TimeNs>(bits) * (1000000000 / bps));
      }
    }
  }
  // The 8-byte frame at 1 Mbit/s: 111 .. 135 us, i.e. 7 400 .. 9 000 frames per second.
  SimBus b;
  CHECK(b.frameTime(classic(1, 8)) == microseconds(135));
}

TEST_CASE("drivers: CAN FD frame durations with bit-rate switch equal the hand-computed figures",
          "[drivers][simbus]") {
  SimBusConfig c;
  c.nominal_bps = 1000000;
  c.data_bps = 5000000;
  // 64 bytes: nominal 17 + 13 = 30 bits; data ESI 1 + DLC 4 + 512 + stuff count 4 + CRC-21
  // + 7 fixed stuff bits = 549 bits at 200 ns: 30 us + 109.8 us = 139.8 us.
  // Worst case: floor((17 + 5 + 512 - 1) / 4) = 133 stuff bits, 4 of them in the 17 arbitration
  // bits: 34 nominal bits + 678 data bits = 34 us + 135.6 us = 169.6 us.
  c.worst_case_stuffing = false;
  {
    Pair p(c);
    REQUIRE(p.na->send(fd(0x140, 64)) == SendResult::Ok);
    p.bus.advance(seconds(1));
    REQUIRE(p.log.events.size() == 1);
    CHECK(p.log.events[0].bits.nominal_bits == 30u);
    CHECK(p.log.events[0].bits.data_bits == 549u);
    CHECK(p.log.events[0].end - p.log.events[0].start == 139800);
  }
  c.worst_case_stuffing = true;
  {
    Pair p(c);
    REQUIRE(p.na->send(fd(0x140, 64)) == SendResult::Ok);
    REQUIRE(p.na->send(fd(0x141, 8)) == SendResult::Ok);
    REQUIRE(p.na->send(fd(0x142, 8, false)) == SendResult::Ok);
    p.bus.advance(seconds(1));
    REQUIRE(p.log.events.size() == 3);
    CHECK(p.log.events[0].bits.nominal_bits == 34u);
    CHECK(p.log.events[0].bits.data_bits == 678u);
    CHECK(p.log.events[0].end - p.log.events[0].start == 169600);
    // 8 bytes: data 1 + 4 + 64 + 4 + 17 + 6 = 96 bits, + floor(85/4) - 4 = 17 stuff bits:
    // 34 us + 113 x 200 ns = 56.6 us.
    CHECK(p.log.events[1].end - p.log.events[1].start == 56600);
    // Without BRS the whole frame runs at the nominal rate: 34 + 113 = 147 bits.
    CHECK(p.log.events[2].end - p.log.events[2].start == microseconds(147));
  }
}

TEST_CASE("drivers: frames a bus or node cannot carry are refused", "[drivers][simbus]") {
  SimBus classic_bus;  // data_bps 0: a classic bus
  SimNodeConfig cfg;
  cfg.fd = true;
  SimNode* a = classic_bus.addNode(cfg);
  CHECK(a->send(fd(0x100, 64)) == SendResult::Invalid);
  CHECK(a->send(classic(0x800, 1)) == SendResult::Invalid);  // not an 11-bit id
  CHECK(a->send(makeFrame(0x100, {1}, MRQP_FW_FRAME_EXT)) == SendResult::Invalid);
  CHECK(a->send(makeFrame(0x100, {1}, MRQP_FW_FRAME_RTR)) == SendResult::Invalid);
  mrqp_fw_frame nine = classic(0x100, 8);
  nine.len = 9;
  CHECK(a->send(nine) == SendResult::Invalid);
  CHECK(a->status().tx_failed == 5u);
  SimBusConfig fdc;
  fdc.data_bps = 5000000;
  SimBus fd_bus(fdc);
  SimNode* classic_only = fd_bus.addNode(SimNodeConfig{});
  CHECK(classic_only->send(fd(0x100, 12)) == SendResult::Invalid);
  CHECK(!classic_only->fdEnabled());
}

TEST_CASE("drivers: arbitration: the lowest identifier wins when nodes start in the same slot",
          "[drivers][simbus]") {
  SimBus bus;
  WireLog log;
  bus.setTap(&log);
  SimNode* n1 = bus.addNode(SimNodeConfig{});
  SimNode* n2 = bus.addNode(SimNodeConfig{});
  SimNode* n3 = bus.addNode(SimNodeConfig{});
  SimNode* rx = bus.addNode(SimNodeConfig{});
  REQUIRE(n1->send(classic(0x300, 8)) == SendResult::Ok);
  REQUIRE(n2->send(classic(0x100, 8)) == SendResult::Ok);
  REQUIRE(n3->send(classic(0x200, 8)) == SendResult::Ok);
  bus.advance(milliseconds(1));
  REQUIRE(log.frames() ==
          std::vector<std::string>{"100#1122334455667788", "200#1122334455667788", "300#1122334455667788"});
  // Back to back: each 8-byte frame is 135 bit times with worst-case stuffing.
  CHECK(log.events[0].start == 0);
  CHECK(log.events[1].start == microseconds(135));
  CHECK(log.events[2].start == microseconds(270));
  CHECK(log.events[0].node == n2->index());
  CHECK(rx->rxPending() == 3u);
  RxFrame f;
  REQUIRE(rx->receive(f) == ReceiveResult::Frame);
  CHECK(f.frame.id == 0x100u);
  CHECK(f.timestamp == microseconds(135));  // delivered at the end of the frame

  // A frame that becomes ready while another is on the wire waits for the bus to be idle, then
  // competes with the frames already waiting: 0x050 (ready at 10 us) beats 0x400 (ready at 0).
  log.clear();
  const TimeNs t0 = bus.now();
  REQUIRE(n1->send(classic(0x700, 8)) == SendResult::Ok);
  REQUIRE(n2->send(classic(0x400, 8)) == SendResult::Ok);
  REQUIRE(n3->sendAt(classic(0x050, 8), t0 + microseconds(10)) == SendResult::Ok);
  bus.advance(milliseconds(1));
  CHECK(log.frames() ==
        std::vector<std::string>{"400#1122334455667788", "050#1122334455667788", "700#1122334455667788"});
}

TEST_CASE("drivers: each node transmits its own queue in order, classic beats FD on equal identifiers",
          "[drivers][simbus]") {
  SimBusConfig c;
  c.data_bps = 5000000;
  Pair p(c);
  REQUIRE(p.na->send(classic(0x300, 1)) == SendResult::Ok);
  REQUIRE(p.na->send(classic(0x100, 1)) == SendResult::Ok);  // behind 0x300 in the same queue
  p.bus.advance(milliseconds(1));
  CHECK(p.log.frames() == std::vector<std::string>{"300#11", "100#11"});

  p.log.clear();
  SimNode* third = p.bus.addNode(SimNodeConfig{});  // classic-only receiver
  (void)third;
  REQUIRE(p.na->send(fd(0x123, 12)) == SendResult::Ok);
  REQUIRE(p.nb->send(classic(0x123, 2)) == SendResult::Ok);
  p.bus.advance(milliseconds(1));
  REQUIRE(p.log.events.size() == 2u);
  CHECK((p.log.events[0].frame.flags & MRQP_FW_FRAME_FD) == 0u);
  CHECK((p.log.events[1].frame.flags & MRQP_FW_FRAME_FD) != 0u);
}

TEST_CASE("drivers: a node alone gets no ACK: TEC +8 per attempt, error passive after 16, never bus-off",
          "[drivers][simbus]") {
  SimBus bus;
  WireLog log;
  bus.setTap(&log);
  SimNode* a = bus.addNode(SimNodeConfig{});
  REQUIRE(a->send(classic(0x123, 8)) == SendResult::Ok);
  // Each attempt: the frame up to the ACK slot (135 - 11 bits), error flag 6 + delimiter 8 +
  // intermission 3: 141 bit times.
  for (int k = 1; k <= 16; ++k) {
    bus.advanceTo(static_cast<TimeNs>(k) * microseconds(141));
    REQUIRE(log.events.size() == static_cast<std::size_t>(k));
    CHECK(log.events.back().outcome == WireOutcome::NoAck);
    CHECK(log.events.back().start == static_cast<TimeNs>(k - 1) * microseconds(141));
    CHECK(a->status().tec == 8 * k);
    const BusState expected = k < 12   ? BusState::ErrorActive
                              : k < 16 ? BusState::ErrorWarning
                                       : BusState::ErrorPassive;
    CHECK(a->status().state == expected);
  }
  // Error passive now: ISO 11898-1 exception 1 keeps the TEC at 128 on further ACK errors, and
  // the node waits 8 more bit times (suspend transmission) between attempts: 149 us apart.
  bus.advance(milliseconds(150));
  CHECK(a->status().tec == 128);
  CHECK(a->status().state == BusState::ErrorPassive);
  CHECK(log.events.size() > 1000u);
  CHECK(log.events[17].start - log.events[16].start == microseconds(149));
  CHECK(bus.stats().delivered == 0u);
  CHECK(a->txPending() == 1u);  // still retrying

  // Error events as SocketCAN reports them: ACK errors, warning at 96, passive at 128.
  std::uint32_t seen = 0;
  std::size_t acks = 0;
  RxFrame ev;
  while (true) {
    const ReceiveResult r = a->receive(ev);
    if (r == ReceiveResult::Empty) {
      break;
    }
    REQUIRE(r == ReceiveResult::ErrorEvent);
    seen |= ev.error.flags;
    acks += (ev.error.flags & bus_error::kAck) != 0u ? 1u : 0u;
    if ((ev.error.flags & bus_error::kWarning) != 0u) {
      CHECK(ev.error.tec == 96);
    }
    if ((ev.error.flags & bus_error::kPassive) != 0u) {
      CHECK(ev.error.tec == 128);
    }
  }
  CHECK((seen & bus_error::kWarning) != 0u);
  CHECK((seen & bus_error::kPassive) != 0u);
  CHECK((seen & bus_error::kBusOff) == 0u);
  CHECK(acks > 16u);

  // A second node appears: the frame is acknowledged, the TEC decrements.
  SimNode* b = bus.addNode(SimNodeConfig{});
  bus.advance(milliseconds(1));
  CHECK(bus.stats().delivered == 1u);
  CHECK(a->status().tec == 127);
  CHECK(a->status().state == BusState::ErrorWarning);
  CHECK(b->rxPending() == 1u);
}

TEST_CASE("drivers: bus-off after 32 transmit errors (TEC +8 each), recovery after 128 x 11 recessive bits",
          "[drivers][simbus]") {
  SimBus bus;
  WireLog log;
  bus.setTap(&log);
  SimNodeConfig no_restart;
  no_restart.auto_recover = false;  // stays bus-off (like restart-ms 0)
  SimNode* a = bus.addNode(no_restart);
  SimNode* b = bus.addNode(SimNodeConfig{});
  a->injectTxErrors(1000);  // noise: every attempt of `a` suffers a bit error
  REQUIRE(a->send(classic(0x123, 8)) == SendResult::Ok);
  bus.advance(milliseconds(20));

  // Attempts: 135 - 13 + 17 = 139 bit times each; after attempt 16 (TEC 128) the node is error
  // passive and suspends 8 more bit times after each attempt. Attempt 32 reaches TEC 256 > 255.
  REQUIRE(log.events.size() == 32u);
  for (std::size_t k = 0; k < 32; ++k) {
    CHECK(log.events[k].outcome == WireOutcome::BitError);
    const TimeNs start =
        k < 16 ? static_cast<TimeNs>(k) * microseconds(139)
               : 16 * microseconds(139) + microseconds(8) + static_cast<TimeNs>(k - 16) * microseconds(147);
    CHECK(log.events[k].start == start);
  }
  const TimeNs off_at = log.events[31].end;
  CHECK(off_at == 16 * microseconds(139) + microseconds(8) + 15 * microseconds(147) + microseconds(139));
  // Receiver: REC +1 per error seen, still error active.
  CHECK(b->status().rec == 32);
  CHECK(b->status().state == BusState::ErrorActive);
  CHECK(b->status().rx_frames == 0u);

  // Recovery: 128 occurrences of 11 recessive bits on an idle bus = 1408 us after bus-off. The
  // node was flushed at bus-off (the frame is lost) and sends are refused meanwhile.
  CHECK(a->status().state == BusState::BusOff);
  CHECK(a->txPending() == 0u);
  CHECK(a->send(classic(0x124, 1)) == SendResult::BusOff);

  SimBus bus2;
  WireLog log2;
  bus2.setTap(&log2);
  SimNode* c = bus2.addNode(SimNodeConfig{});
  SimNode* d = bus2.addNode(SimNodeConfig{});
  (void)d;
  c->injectTxErrors(32);
  REQUIRE(c->send(classic(0x123, 8)) == SendResult::Ok);
  bus2.advanceTo(off_at);
  REQUIRE(c->status().state == BusState::BusOff);
  CHECK(c->status().tec == 256);
  bus2.advanceTo(off_at + microseconds(1408) - 1);
  CHECK(c->status().state == BusState::BusOff);
  bus2.advanceTo(off_at + microseconds(1408));
  CHECK(c->status().state == BusState::ErrorActive);
  CHECK(c->status().tec == 0);
  CHECK(c->status().rec == 0);
  std::uint32_t flags = 0;
  RxFrame ev;
  while (c->receive(ev) != ReceiveResult::Empty) {
    flags |= ev.error.flags;
  }
  CHECK((flags & bus_error::kBit) != 0u);
  CHECK((flags & bus_error::kBusOff) != 0u);
  CHECK((flags & bus_error::kRestarted) != 0u);
  REQUIRE(c->send(classic(0x125, 1)) == SendResult::Ok);
  bus2.advance(milliseconds(1));
  CHECK(log2.frames() == std::vector<std::string>{"125#11"});
}

TEST_CASE("drivers: bus-off recovery counts the 11 recessive bits ending each frame of the others",
          "[drivers][simbus]") {
  SimBus bus;
  SimNode* a = bus.addNode(SimNodeConfig{});
  SimNode* b = bus.addNode(SimNodeConfig{});
  SimNode* c = bus.addNode(SimNodeConfig{});
  (void)c;
  a->injectTxErrors(32);
  REQUIRE(a->send(classic(0x123, 8)) == SendResult::Ok);
  while (a->status().state != BusState::BusOff) {
    bus.advance(microseconds(1));
  }
  // b keeps the bus busy with back-to-back frames from the moment of bus-off: no idle time,
  // one occurrence per frame, so the 128th frame completes the recovery.
  for (int i = 0; i < 127; ++i) {
    REQUIRE(b->send(classic(0x200, 8)) == SendResult::Ok);
    bus.advance(microseconds(135));
    REQUIRE(a->status().state == BusState::BusOff);
  }
  REQUIRE(b->send(classic(0x200, 8)) == SendResult::Ok);
  bus.advance(microseconds(135));
  CHECK(a->status().state == BusState::ErrorActive);
}

TEST_CASE("drivers: identical identifiers with different data from two nodes destroy each other",
          "[drivers][simbus]") {
  SimBus bus;
  WireLog log;
  bus.setTap(&log);
  SimNodeConfig no_restart;
  no_restart.auto_recover = false;
  SimNode* a = bus.addNode(no_restart);
  SimNode* b = bus.addNode(no_restart);
  SimNode* c = bus.addNode(SimNodeConfig{});
  REQUIRE(a->send(makeFrame(0x181, {1})) == SendResult::Ok);
  REQUIRE(b->send(makeFrame(0x181, {2})) == SendResult::Ok);
  bus.advance(milliseconds(10));
  REQUIRE(log.events.size() == 32u);
  for (const WireEvent& e : log.events) {
    CHECK(e.outcome == WireOutcome::Collision);
  }
  CHECK(a->status().state == BusState::BusOff);
  CHECK(b->status().state == BusState::BusOff);
  CHECK(c->status().rx_frames == 0u);
  // Identical frames go out once, both transmitters succeed.
  SimBus bus2;
  SimNode* x = bus2.addNode(SimNodeConfig{});
  SimNode* y = bus2.addNode(SimNodeConfig{});
  SimNode* z = bus2.addNode(SimNodeConfig{});
  REQUIRE(x->send(makeFrame(0x080, {})) == SendResult::Ok);
  REQUIRE(y->send(makeFrame(0x080, {})) == SendResult::Ok);
  bus2.advance(milliseconds(1));
  CHECK(bus2.stats().delivered == 1u);
  CHECK(z->status().rx_frames == 1u);
  CHECK(x->txPending() == 0u);
  CHECK(y->txPending() == 0u);
}

TEST_CASE("drivers: listen-only nodes and classic-only nodes (for FD frames) do not acknowledge",
          "[drivers][simbus]") {
  SimBusConfig c;
  c.data_bps = 2000000;
  SimBus bus(c);
  SimNodeConfig tx;
  tx.fd = true;
  tx.one_shot = true;
  SimNode* a = bus.addNode(tx);
  SimNodeConfig monitor;
  monitor.acknowledge = false;
  monitor.fd = true;
  SimNode* m = bus.addNode(monitor);
  SimNode* classic_only = bus.addNode(SimNodeConfig{});
  REQUIRE(a->send(fd(0x100, 16)) == SendResult::Ok);
  bus.advance(milliseconds(1));
  CHECK(bus.stats().no_ack == 1u);  // one-shot: one attempt, then dropped
  CHECK(a->status().tec == 8);
  CHECK(a->status().tx_failed == 1u);
  CHECK(m->status().rx_frames == 0u);
  // A classic frame is acknowledged by the classic-only node.
  REQUIRE(a->send(classic(0x101, 2)) == SendResult::Ok);
  bus.advance(milliseconds(1));
  CHECK(bus.stats().delivered == 1u);
  CHECK(classic_only->status().rx_frames == 1u);
  CHECK(m->status().rx_frames == 1u);  // a monitor still receives what others acknowledged
}

TEST_CASE("drivers: receive and transmit queues have a fixed capacity, overflow is counted",
          "[drivers][simbus]") {
  SimBus bus;
  SimNodeConfig small;
  small.rx_queue = 4;
  small.tx_queue = 3;
  SimNode* a = bus.addNode(small);
  SimNode* b = bus.addNode(small);
  for (int i = 0; i < 3; ++i) {
    REQUIRE(b->send(classic(0x200 + static_cast<std::uint32_t>(i), 1)) == SendResult::Ok);
  }
  CHECK(b->send(classic(0x210, 1)) == SendResult::QueueFull);
  CHECK(b->status().tx_queue_full == 1u);
  bus.advance(milliseconds(1));
  for (int i = 0; i < 3; ++i) {
    REQUIRE(b->send(classic(0x220 + static_cast<std::uint32_t>(i), 1)) == SendResult::Ok);
  }
  bus.advance(milliseconds(1));
  CHECK(a->rxPending() == 4u);
  CHECK(a->status().rx_overflow == 2u);
  RxFrame f;
  REQUIRE(a->receive(f) == ReceiveResult::Frame);
  CHECK(f.frame.id == 0x200u);  // the oldest kept, the newest lost
}

TEST_CASE("drivers: a disconnected node neither sends, receives nor acknowledges", "[drivers][simbus]") {
  SimBus bus;
  SimNode* a = bus.addNode(SimNodeConfig{});
  SimNode* b = bus.addNode(SimNodeConfig{});
  b->setConnected(false);
  CHECK(b->send(classic(0x1, 1)) == SendResult::Down);
  REQUIRE(a->send(classic(0x2, 1)) == SendResult::Ok);
  bus.advance(microseconds(100));
  CHECK(bus.stats().no_ack == 1u);
  b->setConnected(true);
  bus.advance(milliseconds(1));
  CHECK(bus.stats().delivered == 1u);
  CHECK(b->rxPending() == 1u);
}

TEST_CASE("drivers: node timers fire at their time, also while the bus is busy", "[drivers][simbus]") {
  struct Timer final : SimListener {
    void onReceive(SimNode&, ReceiveResult, const RxFrame&) noexcept override {}
    void onTimer(SimNode& n, TimeNs now) noexcept override {
      fired = now;
      (void)n.send(classic(0x010, 0));
    }
    TimeNs fired = -1;
  } timer;
  SimBus bus;
  WireLog log;
  bus.setTap(&log);
  SimNode* a = bus.addNode(SimNodeConfig{});
  SimNode* b = bus.addNode(SimNodeConfig{});
  b->setListener(&timer);
  b->setTimer(microseconds(50));
  REQUIRE(a->send(classic(0x300, 8)) == SendResult::Ok);  // on the wire 0 .. 135 us
  REQUIRE(a->send(classic(0x301, 8)) == SendResult::Ok);
  bus.advance(milliseconds(1));
  CHECK(timer.fired == microseconds(50));
  // The SYNC-like frame queued at 50 us wins the next arbitration against 0x301.
  CHECK(log.frames() == std::vector<std::string>{"300#1122334455667788", "010#", "301#1122334455667788"});
}
