// mrqp-plant: the world of a scene behind its emulated firmware, on real CAN interfaces
// (docs/loop.md, "Controller and plant in two processes"). It is the other half of
// `mrqp-run SCENE --bus IF…`: the scene's drives, F/T sensors and IMUs (loop::EmulatedRig) sit on
// one simulated bus per bus of the hardware section, and every frame is bridged between that bus
// and the SocketCAN interface given for it. The two processes share nothing but the CAN interfaces.
// The plant's time (--clock): `realtime` (the default) advances it with the wall clock (absolute
// deadlines, a fixed step); `sync` locks it to the controller's SYNCs (lockstep_clock.hpp), for
// machines that cannot keep real time (the HIL VM under software emulation).
//
// The ideal plant here has no controller to follow (that one is in the other process): its robots'
// joints are where their drives put them (a perfect servo), floating bases follow their ground
// contacts, and what no drive moves (objects, mechanisms) stays where the scene put it. The MuJoCo
// plant, where the build has it, is the full physical world.
#include <mrqp/firmware_if/canopen_ids.h>
#include <mrqp/drivers/socketcan_bus.hpp>

#include <poll.h>

#include <algorithm>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "lockstep_clock.hpp"
#include "loop/deadline_clock.hpp"
#include "loop/emulated_rig.hpp"
#include "loop/hardware_check.hpp"
#include "loop/ideal_plant.hpp"
#include "run_options.hpp"
#include "run_scene.hpp"

using namespace mrqp;

namespace {

volatile std::sig_atomic_t g_stop = 0;
void onSignal(int) { g_stop = 1; }

const char* usage() {
  return "usage: mrqp-plant SCENE.yaml --bus IF[,IF...] [--plant ideal|mujoco] [--duration S]\n"
         "                  [--clock realtime|sync] [--step-us N] [--set KEY=VALUE]... [--quiet]\n"
         "  The scene's emulated drives and sensors on the given SocketCAN interfaces (one per bus of\n"
         "  the scene's hardware section, in its order), the plant stepped in real time every N µs\n"
         "  (default 250) until --duration S (default: until SIGINT/SIGTERM). Run the controller\n"
         "  with `mrqp-run SCENE.yaml --bus IF[,IF...]` on the same interfaces.\n"
         "  --clock sync: each bus runs on the wall clock until the controller's first SYNC on it,\n"
         "  then by exactly one SYNC period per SYNC (lock-step; for machines that cannot keep real\n"
         "  time); the plant is then stepped once per advance and --step-us only paces the boot;\n"
         "  --duration counts plant time.\n";
}

struct Options {
  std::string scene;
  std::vector<std::string> buses;
  std::vector<std::string> sets;
  std::string plant;
  double duration = 0.0;
  long step_us = 250;
  bool sync_clock = false;  ///< --clock sync
  bool quiet = false;
};

double positive(const std::string& option, const std::string& v) {
  const double x = run::optionNumber(option, v);
  if (!(x > 0.0)) throw std::invalid_argument(option + ": expected a positive number, got '" + v + "'");
  return x;
}

Options parseOptions(int argc, char** argv, bool* help) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) throw std::invalid_argument(a + " needs a value");
      return argv[++i];
    };
    if (a == "-h" || a == "--help") {
      *help = true;
    } else if (a == "--bus") {
      o.buses = run::interfaceList(a, value());
    } else if (a == "--plant") {
      o.plant = value();
      if (o.plant != "ideal" && o.plant != "mujoco") {
        throw std::invalid_argument("--plant: expected ideal or mujoco, got '" + o.plant + "'");
      }
    } else if (a == "--duration") {
      o.duration = positive(a, value());
    } else if (a == "--step-us") {
      o.step_us = static_cast<long>(positive(a, value()));
      if (o.step_us < 50 || o.step_us > 10000) throw std::invalid_argument("--step-us: expected 50 to 10000");
    } else if (a == "--clock") {
      const std::string c = value();
      if (c != "realtime" && c != "sync") {
        throw std::invalid_argument("--clock: expected realtime or sync, got '" + c + "'");
      }
      o.sync_clock = c == "sync";
    } else if (a == "--set") {
      o.sets.push_back(value());
    } else if (a == "--quiet") {
      o.quiet = true;
    } else if (!a.empty() && a[0] == '-') {
      throw std::invalid_argument("unknown option " + a);
    } else if (o.scene.empty()) {
      o.scene = a;
    } else {
      throw std::invalid_argument("more than one scene file (" + o.scene + ", " + a + ")");
    }
  }
  if (!*help && o.scene.empty()) throw std::invalid_argument("no scene file given");
  if (!*help && o.buses.empty()) throw std::invalid_argument("--bus IF[,IF...] is required");
  return o;
}

struct Bridge {
  loop::EmulatedRig& rig;
  std::vector<std::unique_ptr<drivers::SocketCanBus>>& can;
};

struct Counters {
  std::uint64_t to_plant = 0, to_bus = 0, send_failures = 0;
};

/// What the devices of bus b sent goes out on its interface.
void forwardOut(const Bridge& br, std::size_t b, Counters& n) {
  drivers::RxFrame rx;
  for (;;) {
    const drivers::ReceiveResult r = br.rig.master(b).receive(rx);
    if (r == drivers::ReceiveResult::Empty || r == drivers::ReceiveResult::Failed) break;
    if (r != drivers::ReceiveResult::Frame || rx.own) continue;
    if (br.can[b]->send(rx.frame) == drivers::SendResult::Ok) {
      ++n.to_bus;
    } else {
      ++n.send_failures;
    }
  }
}

void printCounts(double plant_s, const Counters& n) {
  std::printf("mrqp-plant: ran %.3f s: %llu frames to the devices, %llu from them (%llu not sent)", plant_s,
              static_cast<unsigned long long>(n.to_plant), static_cast<unsigned long long>(n.to_bus),
              static_cast<unsigned long long>(n.send_failures));
}

/// Moves the next frame the controller sent on interface `b` (not this process's own) into its
/// simulated bus; false when none is waiting. The frame is left in `rx`.
bool bridgeIn(const Bridge& br, std::size_t b, drivers::RxFrame& rx, Counters& n) {
  for (;;) {
    const drivers::ReceiveResult r = br.can[b]->receive(rx);
    if (r == drivers::ReceiveResult::Empty || r == drivers::ReceiveResult::Failed) return false;
    if (r != drivers::ReceiveResult::Frame || rx.own) continue;
    if (br.rig.master(b).send(rx.frame) == drivers::SendResult::Ok) ++n.to_plant;
    return true;
  }
}

/// --clock realtime: every step (absolute deadlines) the controller's frames enter the simulated
/// buses at the plant's present time, the firmware and the plant run to the present, and what the
/// devices sent goes out.
void runRealtime(const Options& o, const Bridge& br, Counters& n) {
  const drivers::TimeNs step = o.step_us * 1000;
  loop::DeadlineClock clock(step);
  const drivers::TimeNs t0 = clock.start();
  const auto end = static_cast<drivers::TimeNs>(o.duration * 1e9);
  drivers::TimeNs now = 0;
  double next_report = 1.0;
  drivers::RxFrame rx;
  while (g_stop == 0 && (end == 0 || now < end)) {
    for (std::size_t b = 0; b < br.can.size(); ++b) {
      while (bridgeIn(br, b, rx, n)) {}
    }
    br.rig.advanceTo(now);
    for (std::size_t b = 0; b < br.can.size(); ++b) forwardOut(br, b, n);
    now = clock.wait() - t0;
    if (!o.quiet && static_cast<double>(now) * 1e-9 >= next_report) {
      std::fprintf(stderr, "\r  t = %6.1f s  frames in %llu  out %llu  late steps %llu   ", next_report,
                   static_cast<unsigned long long>(n.to_plant), static_cast<unsigned long long>(n.to_bus),
                   static_cast<unsigned long long>(clock.overruns()));
      next_report += 1.0;
    }
  }
  if (!o.quiet) std::fprintf(stderr, "\n");
  printCounts(static_cast<double>(now) * 1e-9, n);
  std::printf(", %llu late steps (worst %.3f ms late)\n", static_cast<unsigned long long>(clock.overruns()),
              static_cast<double>(clock.worstLateness()) * 1e-6);
}

/// --clock sync (lockstep_clock.hpp): the process sleeps until a frame of the controller arrives
/// (or a step passes, for the buses still on the wall clock), hands each frame to its simulated bus
/// at that bus's time and, after each SYNC, runs the bus by one SYNC period, the plant to the
/// latest bus time, and sends what the devices answered. A bus that never carries a SYNC (MIT
/// motors or FD hand boards without a SYNC of their own) stays on the wall clock; a frame that
/// comes after the last SYNC of the run (the safe exit's NMT commands) reaches its device only if
/// another SYNC follows.
void runLockstep(const Options& o, const loop::ResolvedHardware& rh, const Bridge& br, loop::Plant& plant,
                 Counters& n) {
  std::vector<drivers::TimeNs> periods;
  for (const loop::ResolvedBus& b : rh.buses) periods.push_back(std::llround(1e9 / b.cycle_hz));
  plant::LockstepClock lc(periods);
  // One plant step per advance, as far as the latest bus: on a machine slower than the plant, the
  // bridge then answers late instead of falling ever further behind.
  drivers::TimeNs plant_now = 0, plant_ns = 0, buses_ns = 0;
  std::uint64_t plant_steps = 0;
  auto stepPlant = [&]() {
    if (plant_now >= lc.plantTime()) return;
    const drivers::TimeNs t = drivers::monotonicNow();
    plant.step(static_cast<double>(lc.plantTime() - plant_now) * 1e-9);
    plant_now = lc.plantTime();
    ++plant_steps;
    plant_ns += drivers::monotonicNow() - t;
  };
  auto runBus = [&](std::size_t b, drivers::TimeNs to) {
    const drivers::TimeNs t = drivers::monotonicNow();
    br.rig.bus(b).advanceTo(to);
    buses_ns += drivers::monotonicNow() - t;
  };
  std::vector<pollfd> fds;
  for (const auto& c : br.can) fds.push_back(pollfd{c->nativeHandle(), POLLIN, 0});
  const int step_ms = static_cast<int>(std::max(1L, o.step_us / 1000));
  const auto end = static_cast<drivers::TimeNs>(o.duration * 1e9);
  const drivers::TimeNs t0 = drivers::monotonicNow();
  double next_report = 1.0;
  drivers::RxFrame rx;
  while (g_stop == 0 && (end == 0 || lc.plantTime() < end)) {
    // Locked buses move only with the controller's frames: wait for them.
    (void)::poll(fds.data(), fds.size(), lc.allLocked() ? 100 : step_ms);
    for (std::size_t b = 0; b < br.can.size(); ++b) {
      while (bridgeIn(br, b, rx, n)) {
        if (rx.frame.id != MRQP_FW_COB_SYNC) continue;
        runBus(b, lc.onSync(b));
        stepPlant();
        forwardOut(br, b, n);
      }
    }
    // The buses not locked yet follow the wall clock in whole steps (one plant step per step).
    const drivers::TimeNs wall = drivers::monotonicNow() - t0;
    if (lc.onWall(wall - wall % (o.step_us * 1000))) {
      for (std::size_t b = 0; b < br.can.size(); ++b) {
        if (lc.locked(b)) continue;
        runBus(b, lc.busTime(b));
        forwardOut(br, b, n);
      }
      stepPlant();
    }
    if (!o.quiet && static_cast<double>(lc.plantTime()) * 1e-9 >= next_report) {
      std::fprintf(stderr, "\r  t = %6.1f s (plant)  frames in %llu  out %llu   ", next_report,
                   static_cast<unsigned long long>(n.to_plant), static_cast<unsigned long long>(n.to_bus));
      next_report += 1.0;
    }
  }
  if (!o.quiet) std::fprintf(stderr, "\n");
  const double wall_s = static_cast<double>(drivers::monotonicNow() - t0) * 1e-9;
  printCounts(static_cast<double>(lc.plantTime()) * 1e-9, n);
  std::printf(" in %.3f s of wall time\nmrqp-plant: lock-step: SYNCs per bus", wall_s);
  for (std::size_t b = 0; b < lc.busCount(); ++b) {
    std::printf(" %s %llu%s", rh.buses[b].decl.name.c_str(), static_cast<unsigned long long>(lc.syncs(b)),
                lc.locked(b) ? "" : " (never locked)");
  }
  std::printf(
      "\nmrqp-plant: lock-step: %llu plant steps, %.3f s in the plant, %.3f s in the firmware and buses\n",
      static_cast<unsigned long long>(plant_steps), static_cast<double>(plant_ns) * 1e-9,
      static_cast<double>(buses_ns) * 1e-9);
}

int plantMain(int argc, char** argv) {
  bool help = false;
  Options o;
  try {
    o = parseOptions(argc, argv, &help);
  } catch (const std::invalid_argument& e) {
    std::fprintf(stderr, "mrqp-plant: %s\n%s", e.what(), usage());
    return 2;
  }
  if (help) {
    std::printf("%s", usage());
    return 0;
  }

  // ---- the scene, its hardware and the plant (as mrqp-run loads them) ----
  const std::unique_ptr<run::RunScene> rs = run::loadRunScene(o.scene, o.sets, o.plant);
  problem::MultiRobotProblem& p = *rs->scene.problem;
  const loop::ResolvedHardware& rh = rs->hardware;
  std::unique_ptr<loop::Plant>& plant = rs->plant;
  // No controller solves in this process: the ideal plant follows no accelerations.
  if (auto* ideal = dynamic_cast<loop::IdealPlant*>(plant.get())) ideal->setFollowing(false);
  loop::EmulatedRig rig(rh, p, *plant);
  // One plant step per bridge step at most: the plant keeps pace with the wall clock on a slow
  // machine (a virtual machine under emulation) instead of stepping finer than it can afford.
  rig.setMaxPlantStep(o.step_us * 1000);

  if (o.buses.size() != rig.busCount()) {
    throw std::runtime_error("--bus: " + std::to_string(o.buses.size()) +
                             " interfaces given, the hardware section has " + std::to_string(rig.busCount()) +
                             " buses");
  }
  std::vector<std::unique_ptr<drivers::SocketCanBus>> can;
  for (std::size_t b = 0; b < o.buses.size(); ++b) {
    drivers::SocketCanConfig c;
    c.interface = o.buses[b];
    c.fd = rh.buses[b].decl.data_bitrate != 0;
    c.error_frames = false;
    c.timestamps = false;
    auto bus = std::make_unique<drivers::SocketCanBus>();
    std::string err;
    if (!bus->open(c, &err)) throw std::runtime_error("--bus " + o.buses[b] + ": " + err);
    can.push_back(std::move(bus));
  }
  if (!o.quiet) {
    std::printf("mrqp-plant: %s: plant %s, %zu buses (", o.scene.c_str(), plant->kind(), can.size());
    for (std::size_t b = 0; b < can.size(); ++b) {
      std::printf("%s%s on %s", b ? ", " : "", rh.buses[b].decl.name.c_str(), o.buses[b].c_str());
    }
    std::printf("), step %ld µs, clock %s\n", o.step_us, o.sync_clock ? "sync (lock-step)" : "realtime");
    std::fflush(stdout);
  }

  std::signal(SIGINT, onSignal);
  std::signal(SIGTERM, onSignal);
  const Bridge br{rig, can};
  Counters n;
  if (o.sync_clock) {
    runLockstep(o, rh, br, *plant, n);
  } else {
    runRealtime(o, br, n);
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return plantMain(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "mrqp-plant: %s\n", e.what());
  } catch (...) {
    std::fprintf(stderr, "mrqp-plant: unknown error\n");
  }
  return 1;
}
