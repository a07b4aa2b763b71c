// mrqp-plant: the world of a scene behind its emulated firmware, on real CAN interfaces
// (docs/loop.md, "Controller and plant in two processes"). It is the other half of
// `mrqp-run SCENE --bus IF…`: the scene's drives, F/T sensors and IMUs (loop::EmulatedRig) sit on
// one simulated bus per bus of the hardware section, and every frame is bridged between that bus
// and the SocketCAN interface given for it. The plant advances in real time (absolute deadlines,
// a fixed step); the two processes share nothing but the CAN interfaces.
//
// The ideal plant here has no controller to follow (that one is in the other process): its robots'
// joints are where their drives put them (a perfect servo), floating bases follow their ground
// contacts, and what no drive moves (objects, mechanisms) stays where the scene put it. The MuJoCo
// plant, where the build has it, is the full physical world.
#include <mrqp/drivers/socketcan_bus.hpp>

#include <csignal>
#include <cstdio>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

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
         "                  [--step-us N] [--set KEY=VALUE]... [--quiet]\n"
         "  The scene's emulated drives and sensors on the given SocketCAN interfaces (one per bus of\n"
         "  the scene's hardware section, in its order), the plant stepped in real time every N µs\n"
         "  (default 250) until --duration S (default: until SIGINT/SIGTERM). Run the controller\n"
         "  with `mrqp-run SCENE.yaml --bus IF[,IF...]` on the same interfaces.\n";
}

struct Options {
  std::string scene;
  std::vector<std::string> buses;
  std::vector<std::string> sets;
  std::string plant;
  double duration = 0.0;
  long step_us = 250;
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
    std::printf("), step %ld µs\n", o.step_us);
    std::fflush(stdout);
  }

  std::signal(SIGINT, onSignal);
  std::signal(SIGTERM, onSignal);
  const drivers::TimeNs step = o.step_us * 1000;
  loop::DeadlineClock clock(step);
  const drivers::TimeNs t0 = clock.start();
  const auto end = static_cast<drivers::TimeNs>(o.duration * 1e9);
  std::uint64_t to_plant = 0, to_bus = 0, send_failures = 0;
  drivers::TimeNs now = 0;
  double next_report = 1.0;
  drivers::RxFrame rx;
  while (g_stop == 0 && (end == 0 || now < end)) {
    // The controller's frames enter the simulated buses at the plant's present time...
    for (std::size_t b = 0; b < can.size(); ++b) {
      for (;;) {
        const drivers::ReceiveResult r = can[b]->receive(rx);
        if (r == drivers::ReceiveResult::Empty || r == drivers::ReceiveResult::Failed) break;
        if (r != drivers::ReceiveResult::Frame || rx.own) continue;
        if (rig.master(b).send(rx.frame) == drivers::SendResult::Ok) ++to_plant;
      }
    }
    // ...the firmware and the plant run to the present...
    rig.advanceTo(now);
    // ...and what the devices sent goes out on the interfaces.
    for (std::size_t b = 0; b < can.size(); ++b) {
      for (;;) {
        const drivers::ReceiveResult r = rig.master(b).receive(rx);
        if (r == drivers::ReceiveResult::Empty || r == drivers::ReceiveResult::Failed) break;
        if (r != drivers::ReceiveResult::Frame || rx.own) continue;
        if (can[b]->send(rx.frame) == drivers::SendResult::Ok) {
          ++to_bus;
        } else {
          ++send_failures;
        }
      }
    }
    now = clock.wait() - t0;
    if (!o.quiet && static_cast<double>(now) * 1e-9 >= next_report) {
      std::fprintf(stderr, "\r  t = %6.1f s  frames in %llu  out %llu  late steps %llu   ", next_report,
                   static_cast<unsigned long long>(to_plant), static_cast<unsigned long long>(to_bus),
                   static_cast<unsigned long long>(clock.overruns()));
      next_report += 1.0;
    }
  }
  if (!o.quiet) std::fprintf(stderr, "\n");
  std::printf(
      "mrqp-plant: ran %.3f s: %llu frames to the devices, %llu from them (%llu not sent), %llu late steps "
      "(worst %.3f ms late)\n",
      static_cast<double>(now) * 1e-9, static_cast<unsigned long long>(to_plant),
      static_cast<unsigned long long>(to_bus), static_cast<unsigned long long>(send_failures),
      static_cast<unsigned long long>(clock.overruns()), static_cast<double>(clock.worstLateness()) * 1e-6);
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
