// mrqp-run's command line (see run_options.hpp).
#include "run_options.hpp"

#include <algorithm>
#include <cstdlib>
#include <stdexcept>

namespace mrqp::run {

const char* runUsage() noexcept {
  return "usage: mrqp-run SCENE.yaml --out DIR [--plant mujoco|ideal] [--bus sim|IFNAME[,IFNAME...]]\n"
         "                [--cycles N | --duration S] [--realtime | --paced]\n"
         "                [--clock wall|cycles [--pace F]]\n"
         "                [--fault KIND@SECONDS[:DEVICE]]... [--set KEY=VALUE]... [--no-force-control]\n"
         "                [--no-plots] [--quiet]\n"
         "  Runs the scene as a controller: the loop reads the drives over CAN, solves the QP and\n"
         "  streams setpoints; the plant and its emulated firmware sit behind the bus.\n"
         "  KIND: heartbeat-loss, bus-off, frame-loss, corrupt-frames, nan-feedback, stale-ft, infeasible.\n"
         "  DEVICE: a drive ENTITY.JOINT or a bus name of the scene's hardware section.\n"
         "  --paced: cycles at the scene's period on the wall clock (as --realtime, without its set-up).\n"
         "  --clock cycles (SocketCAN): the drivers' time (heartbeat and other timeouts) is the cycles run\n"
         "  times the period, not the wall clock, for a plant lock-stepped to the SYNCs (mrqp-plant\n"
         "  --clock sync); the cycles are still paced on the wall clock, F periods apart with --pace F\n"
         "  (slow motion, F >= 1, for a machine that cannot run the loop and its plant in real time).\n"
         "  --no-force-control: every admittance of the scene's force_control section in mode off.\n";
}

double optionNumber(const std::string& opt, const std::string& v) {
  char* end = nullptr;
  const double d = std::strtod(v.c_str(), &end);
  if (v.empty() || *end != '\0') throw std::invalid_argument(opt + ": expected a number, got '" + v + "'");
  return d;
}

std::vector<std::string> interfaceList(const std::string& opt, const std::string& v) {
  std::vector<std::string> out;
  std::size_t p = 0;
  while (p <= v.size()) {
    const std::size_t c = std::min(v.find(',', p), v.size());
    if (c == p) throw std::invalid_argument(opt + ": empty interface name in '" + v + "'");
    out.push_back(v.substr(p, c - p));
    p = c + 1;
  }
  return out;
}

RunOptions parseRunOptions(int argc, char** argv, bool* help) {
  RunOptions o;
  *help = false;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) throw std::invalid_argument(a + " needs a value");
      return argv[++i];
    };
    if (a == "-h" || a == "--help") {
      *help = true;
      return o;
    } else if (a == "--out") {
      o.out = value();
    } else if (a == "--plant") {
      o.plant = value();
      if (o.plant != "ideal" && o.plant != "mujoco")
        throw std::invalid_argument("--plant: expected mujoco or ideal");
    } else if (a == "--bus") {
      const std::string v = value();
      if (v != "sim") o.buses = interfaceList(a, v);
    } else if (a == "--cycles") {
      const double n = optionNumber(a, value());
      if (!(n >= 1.0) || n != static_cast<double>(static_cast<long>(n)))
        throw std::invalid_argument("--cycles: expected an integer >= 1");
      o.cycles = static_cast<long>(n);
    } else if (a == "--duration") {
      o.duration = optionNumber(a, value());
      if (!(o.duration > 0.0)) throw std::invalid_argument("--duration: expected seconds > 0");
    } else if (a == "--realtime") {
      o.realtime = true;
    } else if (a == "--paced") {
      o.paced = true;
    } else if (a == "--clock") {
      const std::string v = value();
      if (v != "wall" && v != "cycles")
        throw std::invalid_argument("--clock: expected wall or cycles, got '" + v + "'");
      o.cycle_clock = v == "cycles";
    } else if (a == "--pace") {
      o.pace = optionNumber(a, value());
      if (!(o.pace >= 1.0 && o.pace <= 100.0))
        throw std::invalid_argument("--pace: expected a factor in [1, 100]");
    } else if (a == "--quiet") {
      o.quiet = true;
    } else if (a == "--no-plots") {
      o.plots = false;
    } else if (a == "--no-force-control") {
      o.force_control = false;
    } else if (a == "--fault") {
      o.faults.push_back(loop::parseFaultRequest(value()));
    } else if (a == "--set") {
      o.sets.push_back(value());
    } else if (!a.empty() && a[0] == '-') {
      throw std::invalid_argument("unknown option " + a);
    } else if (o.scene.empty()) {
      o.scene = a;
    } else {
      throw std::invalid_argument("one scene file only (got '" + o.scene + "' and '" + a + "')");
    }
  }
  if (o.scene.empty()) throw std::invalid_argument("a scene file is required");
  if (o.out.empty()) throw std::invalid_argument("--out DIR is required");
  if (o.cycles > 0 && o.duration > 0.0)
    throw std::invalid_argument("--cycles and --duration exclude each other");
  if (o.pace != 1.0 && !o.cycle_clock) throw std::invalid_argument("--pace needs --clock cycles");
  return o;
}

}  // namespace mrqp::run
