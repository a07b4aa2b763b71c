// mrqp-run: runs a scene as a controller (docs/loop.md). The loop reads its drives over CAN,
// estimates, solves the multi-robot QP and streams setpoints; behind the bus sit the plant and the
// emulated firmware (--bus sim, one simulated clock: deterministic) or real interfaces.
#include <mrqp/drivers/socketcan_bus.hpp>

#include <sys/stat.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#ifdef MRQP_RUN_HAVE_COLLISION
#include "collision/collision_watch.hpp"
#endif
#include "carry_watch.hpp"
#include "estimation/estimation_yaml.hpp"
#include "estimation_run.hpp"
#include "force/admittance_hook.hpp"
#include "force/force_control_yaml.hpp"
#include "hands_recorder.hpp"
#include "loop/controller.hpp"
#include "loop/deadline_clock.hpp"
#include "loop/device_lifecycle.hpp"
#include "loop/emulated_rig.hpp"
#include "loop/fault_injector.hpp"
#include "loop/hardware_check.hpp"
#include "loop/ideal_plant.hpp"
#include "loop/log_ring.hpp"
#include "loop/realtime.hpp"
#include "loop/timeline.hpp"
#include "motion_track.hpp"
#include "pen_click_watch.hpp"
#include "run_options.hpp"
#include "run_report.hpp"
#include "run_scene.hpp"
#include "scene/scene_builder.hpp"
#include "scene/yaml_reader.hpp"
#include "summary_fields.hpp"
#include "waypoint_trajectory.hpp"

#ifdef MRQP_RUN_COUNTS_ALLOCATIONS
#include "counting_allocator.hpp"
#endif

using namespace mrqp;

namespace {

/// Drains the log ring into DIR/log.csv until stopped (a non-real-time thread).
class LogWriter {
 public:
  LogWriter(loop::LogRing& ring, const std::string& path) : ring_(ring), row_(ring.width()) {
    file_ = std::fopen(path.c_str(), "w");
    if (file_ == nullptr) throw std::runtime_error(path + ": cannot write");
    const auto& cols = ring.columns();
    for (std::size_t i = 0; i < cols.size(); ++i) std::fprintf(file_, "%s%s", i ? "," : "", cols[i].c_str());
    std::fprintf(file_, "\n");
    thread_ = std::thread([this] { run(); });
  }
  ~LogWriter() { stop(); }
  void stop() {
    if (thread_.joinable()) {
      stop_.store(true);
      thread_.join();
    }
    if (file_ != nullptr) {
      std::fclose(file_);
      file_ = nullptr;
    }
  }

 private:
  void run() {
    for (;;) {
      bool any = false;
      while (ring_.pop(row_.data())) {
        any = true;
        for (std::size_t i = 0; i < row_.size(); ++i) std::fprintf(file_, "%s%.9g", i ? "," : "", row_[i]);
        std::fprintf(file_, "\n");
      }
      if (!any) {
        if (stop_.load()) return;
        std::this_thread::sleep_for(std::chrono::milliseconds(2));
      }
    }
  }
  loop::LogRing& ring_;
  std::vector<double> row_;
  FILE* file_ = nullptr;
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

std::string flagNames(std::uint32_t flags) { return drivers::faultFlagsStr(flags); }

/// SIGINT/SIGTERM during the loop: the loop ends after the cycle under way and the safe exit runs
/// as after the last cycle (docs/loop.md, "Safety").
volatile std::sig_atomic_t g_interrupted = 0;
void onInterrupt(int) { g_interrupted = 1; }

/// The loop thread's allocations are counted while armed (tests/support's counting allocator);
/// a build without it (sanitizers) counts nothing and reports −1.
void armAllocationCounter(bool on) noexcept {
#ifdef MRQP_RUN_COUNTS_ALLOCATIONS
  testing::armThreadCounter(on);
#else
  (void)on;
#endif
}
long countedAllocations() noexcept {
#ifdef MRQP_RUN_COUNTS_ALLOCATIONS
  return testing::armedAllocationCount();
#else
  return -1;
#endif
}

int runMain(int argc, char** argv) {
  bool help = false;
  run::RunOptions o;
  try {
    o = run::parseRunOptions(argc, argv, &help);
  } catch (const std::invalid_argument& e) {
    std::fprintf(stderr, "mrqp-run: %s\n%s", e.what(), run::runUsage());
    return 2;
  }
  if (help) {
    std::printf("%s", run::runUsage());
    return 0;
  }
  for (std::size_t i = 1; i <= o.out.size(); ++i) {  // mkdir -p
    if (i == o.out.size() || o.out[i] == '/') {
      const std::string part = o.out.substr(0, i);
      if (::mkdir(part.c_str(), 0777) != 0 && errno != EEXIST) {
        throw std::runtime_error(o.out + ": cannot create the output directory: " + std::strerror(errno));
      }
    }
  }

  // ---- the scene with --set applied, its hardware section and the plant ----
  const std::unique_ptr<run::RunScene> rs = run::loadRunScene(o.scene, o.sets, o.plant);
  const std::string& text = rs->text;
  const scene::ModelRegistry& models = rs->models;
  const scene::SceneSpec& spec = rs->spec;
  scene::Scene& sc = rs->scene;
  problem::MultiRobotProblem& p = *sc.problem;
  const double dt = sc.settings.dt;
  const auto period = static_cast<drivers::TimeNs>(std::llround(dt * 1e9));
  const loop::ResolvedHardware& rh = rs->hardware;
  std::unique_ptr<loop::Plant>& plant = rs->plant;
  auto* ideal = dynamic_cast<loop::IdealPlant*>(plant.get());

  // ---- the buses ----
  std::unique_ptr<loop::EmulatedRig> rig;
  std::vector<std::unique_ptr<drivers::SocketCanBus>> can;
  std::vector<drivers::Bus*> buses;
  const bool sim = o.buses.empty();
  if (sim) {
    rig = std::make_unique<loop::EmulatedRig>(rh, p, *plant);
    for (std::size_t b = 0; b < rig->busCount(); ++b) buses.push_back(&rig->master(b));
  } else {
    if (o.buses.size() != rh.buses.size()) {
      throw std::runtime_error("--bus: " + std::to_string(o.buses.size()) +
                               " interfaces given, the hardware section has " +
                               std::to_string(rh.buses.size()) + " buses");
    }
    for (std::size_t b = 0; b < o.buses.size(); ++b) {
      const std::string& name = o.buses[b];
      drivers::SocketCanConfig c;
      c.interface = name;
      c.fd = rh.buses[b].decl.data_bitrate != 0;
      c.receive_own = true;           // the arm master takes a boot-up only after its reset's own echo
      c.timestamps = !o.cycle_clock;  // --clock cycles: a frame's time is the cycle that reads it
      auto bus = std::make_unique<drivers::SocketCanBus>();
      std::string err;
      if (!bus->open(c, &err)) throw std::runtime_error("--bus " + name + ": " + err);
      buses.push_back(bus.get());
      can.push_back(std::move(bus));
    }
  }

  // On simulated buses the drives are the plant's emulated ones: they interpolate only where the
  // plant's do (the ideal plant's reach each setpoint at once), whatever the scene's hardware
  // section says of the real ones (docs/loop.md, step 2).
  loop::ResolvedHardware controller_hw = rh;
  if (sim && !plant->drivesInterpolate()) {
    for (auto& robot : controller_hw.robots) robot.interpolating_drives = false;
  }
  loop::Controller ctrl(p, controller_hw, buses);
  std::vector<std::string> task_names(static_cast<std::size_t>(p.taskCapacity()));
  for (const auto& [name, id] : sc.tasks) task_names[static_cast<std::size_t>(id)] = name;
  std::vector<std::string> contact_names(static_cast<std::size_t>(p.contactCapacity()));
  for (const auto& [name, id] : sc.contacts) contact_names[static_cast<std::size_t>(id)] = name;
  loop::LogRing ring;
  ctrl.attachLog(ring, task_names, contact_names);
  // The scene's estimation section (docs/estimation.md): its hook, log columns and summary fields.
  run::EstimationRun estimator_run(
      estimation::readEstimation(text, o.scene, spec, sc, rh), ctrl, ring,
      o.cycles > 0 ? o.cycles : std::lround((o.duration > 0.0 ? o.duration : sc.settings.duration) / dt));
  ring.freeze(1u << 13);  // 8 s of rows at 1 kHz: the writer drains every 2 ms
  loop::FaultInjector faults(o.faults, rig.get(), ctrl, rh);
  loop::Timeline timeline = loop::Timeline::read(text, o.scene, sc);
  if (!timeline.events().empty()) ctrl.addHook(timeline);
  // The scene's trajectories (waypoint_trajectory.hpp), before the admittance: it takes a carried
  // task's moving target as its nominal position.
  run::WaypointTrajectory trajectory = run::WaypointTrajectory::read(text, o.scene, sc);
  if (!trajectory.empty()) ctrl.addHook(trajectory);
  // The force control of the scene's force_control section (docs/force-control.md).
  const force::ForceControlSpec force_spec = force::readForceControl(text, o.scene, sc, rh, dt);
  force::AdmittanceHook admittance(ctrl, force_spec, !o.force_control);
  if (admittance.size() > 0) ctrl.addHook(admittance);

  long cycles = o.cycles;
  if (cycles <= 0) cycles = std::lround((o.duration > 0.0 ? o.duration : sc.settings.duration) / dt);
  std::vector<double> cycle_us(static_cast<std::size_t>(cycles), 0.0);
  run::MotionTrack motion(*plant, p, static_cast<double>(cycles) * dt, 30.0);
  // A carried object measured on the plant's state (carry_watch.hpp): summary.json's box_* fields.
  std::unique_ptr<scene::Scene> carry_shadow;
  std::unique_ptr<run::CarryWatch> carry;
  if (!trajectory.empty()) {
    carry_shadow = std::make_unique<scene::Scene>(scene::buildScene(spec, models));
    carry = std::make_unique<run::CarryWatch>(sc, *carry_shadow->problem, *plant, trajectory, &admittance,
                                              static_cast<double>(cycles) * dt);
  }
  // summary.json's `hands`, force.csv and the force plots (docs/force-control.md): the plant's
  // drive torques only behind simulated buses.
  run::HandsRecorder hands(admittance, p, sim ? plant.get() : nullptr, cycles, dt);
  run::PenClickWatch pen_watch(spec, models, p, *plant, cycles);  // a pen scene's fields (docs/scenes.md)
#ifdef MRQP_RUN_HAVE_COLLISION
  // summary.json's min_distance_m: every collision pair measured on the plant's state between
  // cycles, on a second problem of the scene (docs/collision.md).
  scene::Scene shadow = scene::buildScene(spec, models);
  collision::CollisionWatch watch(p, *shadow.problem);
  std::vector<int> handles;
  for (int i = 0; i < p.entityCount(); ++i) handles.push_back(plant->entityHandle(p.entity(i).name()));
  auto plantState = [&](int i, Eigen::VectorXd& q, Eigen::VectorXd& v) {
    const int h = handles[static_cast<std::size_t>(i)];
    if (h >= 0) {
      plant->entityState(h, q, v);
    } else {  // not simulated by the plant: the controller's estimate
      q = p.entity(i).q();
      v = p.entity(i).v();
    }
  };
#endif

  if (!o.quiet) {
    std::printf("mrqp-run: %s: %d entities, %zu tasks, %zu contacts; plant %s, %s; %ld cycles of %g ms\n",
                o.scene.c_str(), p.entityCount(), sc.tasks.size(), sc.contacts.size(), plant->kind(),
                sim ? "simulated buses" : "SocketCAN", cycles, dt * 1e3);
    for (const loop::ResolvedBus& b : rh.buses) std::printf("%s", b.report.c_str());
    for (const std::string& n : ctrl.notices()) std::printf("mrqp-run: note: %s\n", n.c_str());
  }
  if (o.realtime) {
    const loop::RealtimeReport r = loop::setupRealtime();
    for (const std::string& m : r.messages) std::printf("mrqp-run: realtime: %s\n", m.c_str());
  }
  LogWriter writer(ring, o.out + "/log.csv");

  // ---- boot: every device booted and enabled ----
  // Pacing (wall clock, absolute deadlines) and the time base: with simulated buses the drivers,
  // the buses and the plant run on the simulated clock even when the cycles are paced; with
  // --clock cycles the SocketCAN drivers run on the cycles (cycles × period, paced --pace periods apart).
  loop::DeadlineClock clock(static_cast<drivers::TimeNs>(std::llround(static_cast<double>(period) * o.pace)));
  const bool paced = o.realtime || o.paced || !sim;
  const drivers::TimeNs wall0 = paced ? clock.start() : 0;
  drivers::TimeNs now = sim ? 0 : wall0;
  auto next = [&]() {
    const drivers::TimeNs deadline = paced ? clock.wait() : 0;
    return sim || o.cycle_clock ? now + period : deadline;  // --clock cycles: cycles × period
  };
  // A signal from here on ends the boot or the loop (after the cycle under way) with the safe exit.
  std::signal(SIGINT, onInterrupt);
  std::signal(SIGTERM, onInterrupt);
  // From here on every way out (a failed boot, an exception before or during the loop) runs the
  // same safe exit on what was started (docs/loop.md, "Safety").
  const double boot_timeout_s = 10.0;
  const loop::LifecycleResult booted = loop::bootDevices(ctrl, now, period, rig.get(), boot_timeout_s, next,
                                                         [] { return g_interrupted != 0; });
  if (!booted.done && g_interrupted != 0) {  // a signal during the boot: nothing ran, nothing failed
    const loop::LifecycleResult exited = loop::exitDevices(ctrl, now, period, rig.get(), 2.0, next);
    writer.stop();
    std::printf("mrqp-run: interrupted by a signal during the boot after %ld cycles: %s\n", booted.cycles,
                loop::describeSafeExit(rh, exited).c_str());
    return 1;
  }
  if (!booted.done) {
    const std::vector<std::string> why = loop::describeBootFailure(ctrl);  // before the exit rewrites it
    const loop::LifecycleResult exited = loop::exitDevices(ctrl, now, period, rig.get(), 2.0, next);
    writer.stop();
    std::fprintf(stderr,
                 "mrqp-run: the devices did not boot and enable: %s after %ld cycles (flags seen: %s)\n",
                 loop::bootFailed(booted) ? "a device's boot failed" : "time limit reached", booted.cycles,
                 flagNames(booted.flags).c_str());
    for (const std::string& line : why) std::fprintf(stderr, "mrqp-run:   %s\n", line.c_str());
    std::fprintf(stderr, "mrqp-run: %s\n", loop::describeSafeExit(rh, exited).c_str());
    return 1;
  }
  // An exception between here and the safe exit below (set-up of the loop, a watcher of the run)
  // still stops the devices: the guard runs the safe exit while the exception passes.
  bool devices_exited = false;
  struct ExitOnUnwind {
    std::function<void()> run;
    ~ExitOnUnwind() { run(); }
  } exit_on_unwind{[&]() {
    if (devices_exited) return;
    devices_exited = true;
    const loop::LifecycleResult exited = loop::exitDevices(ctrl, now, period, rig.get(), 2.0, next);
    std::fprintf(stderr, "mrqp-run: stopped by an error after the boot: %s\n",
                 loop::describeSafeExit(rh, exited).c_str());
  }};
  const long boot = booted.cycles;
  if (!o.quiet)
    std::printf("mrqp-run: devices ready after %ld cycles (%.3f s)\n", boot, static_cast<double>(boot) * dt);
  std::fflush(stdout);  // a program that waits for this line sees it now

  // ---- the loop ----
  std::vector<std::uint64_t> busy0;
  if (rig) {
    for (std::size_t b = 0; b < rig->busCount(); ++b)
      busy0.push_back(static_cast<std::uint64_t>(rig->bus(b).stats().busy_ns));
  }
  const drivers::TimeNs loop_start = now;
  long misses = 0;
  const std::uint64_t overruns0 = clock.overruns();
  const long progress_every = std::max(1L, std::lround(0.5 / dt));
  const long planned = cycles;
  for (long k = 0; k < cycles; ++k) {
    if (g_interrupted != 0) {  // the cycles run so far are the run
      cycles = k;
      cycle_us.resize(static_cast<std::size_t>(k));
      break;
    }
    faults.beforeCycle(static_cast<double>(k) * dt, now);
    armAllocationCounter(true);
    ctrl.cycle(now);
    armAllocationCounter(false);
    faults.afterCycle();
    hands.sample(k);
    estimator_run.record(static_cast<double>(k) * dt);
#ifdef MRQP_RUN_HAVE_COLLISION
    watch.measure(plantState);
#endif
    pen_watch.measure(static_cast<double>(k) * dt);
    if (carry) carry->sample(static_cast<double>(k) * dt);
    if (o.plots && motion.due(static_cast<double>(k) * dt)) motion.capture(static_cast<double>(k) * dt);
    if (ideal != nullptr) ideal->setFollowing(!ctrl.holding());  // stands still while held
    const drivers::TimeNs total = ctrl.lastTiming().total_ns;
    cycle_us[static_cast<std::size_t>(k)] = static_cast<double>(total) * 1e-3;
    if (!paced && total > period) ++misses;
    if (rig) rig->advanceTo(now + period);
    if (!o.quiet && (k % progress_every == 0 || k + 1 == cycles)) {
      std::fprintf(stderr, "\r  t = %6.2f s  cycle %5.0f µs  qp %s%s   ", static_cast<double>(k) * dt,
                   cycle_us[static_cast<std::size_t>(k)],
                   ctrl.lastStatus() == qp::QpStatus::Optimal ? "optimal" : "NOT optimal",
                   ctrl.safeStopped() ? "  SAFE STOP" : "");
    }
    now = next();
  }
  if (!o.quiet) std::fprintf(stderr, "\n");
  if (cycles < planned) {
    std::printf("mrqp-run: interrupted by a signal after %ld of %ld cycles: safe exit\n", cycles, planned);
  }
  if (paced) misses = static_cast<long>(clock.overruns() - overruns0);
  writer.stop();
  const double loop_s = static_cast<double>(now - loop_start) * 1e-9;
  std::vector<std::uint64_t> busy1;
  if (rig) {
    for (std::size_t b = 0; b < rig->busCount(); ++b)
      busy1.push_back(static_cast<std::uint64_t>(rig->bus(b).stats().busy_ns));
  }
  // ---- the safe exit: the drives stopped and left in the NMT state of hardware.safe_exit ----
  devices_exited = true;
  const loop::LifecycleResult exited = loop::exitDevices(ctrl, now, period, rig.get(), 2.0, next);

  // ---- summary ----
  run::RunSummary s;
  s.scene = o.scene;
  s.cycles = cycles;
  s.period_s = dt;
  s.deadline_misses = misses;
  s.allocations_in_loop = countedAllocations();
  s.log_records_dropped = static_cast<long>(ring.dropped());
  std::vector<double> sorted = cycle_us;
  std::sort(sorted.begin(), sorted.end());
  s.median_us = run::percentile(sorted, 0.5);
  s.p99_us = run::percentile(sorted, 0.99);
  s.p999_us = run::percentile(sorted, 0.999);
  s.max_us = sorted.empty() ? 0.0 : sorted.back();
  if (ctrl.safeStopped()) {
    char buf[256];
    std::snprintf(buf, sizeof buf, "%s at t = %.4f s (cycle %llu)%s%s%s%s",
                  loop::stopReasonStr(ctrl.stopReason()), static_cast<double>(ctrl.stopTime()) * 1e-9,
                  static_cast<unsigned long long>(ctrl.stopCycle()),
                  ctrl.stopDevice().empty() ? "" : ", device ", ctrl.stopDevice().c_str(),
                  ctrl.stopFlags() != 0u ? ": " : "",
                  ctrl.stopFlags() != 0u ? flagNames(ctrl.stopFlags()).c_str() : "");
    s.safe_stop = buf;
  }
  for (const auto& [name, id] : sc.tasks) s.task_errors_final.emplace_back(name, p.taskError(id).norm());
  for (const loop::RobotIo& r : ctrl.robots()) {
    s.joint_tracking_error_max_rad.emplace_back(r.name, r.tracking_error_max);
    const problem::Entity& e = p.entity(r.entity);
    if (e.floatingBase() && sim) {
      Eigen::VectorXd q(e.nq()), v(e.nv());
      plant->entityState(plant->entityHandle(r.name), q, v);
      s.base_estimate_error_m.emplace_back(r.name, (q.head<3>() - e.q().head<3>()).norm());
    }
  }
  for (std::size_t b = 0; b < rh.buses.size(); ++b) {
    double load = rh.buses[b].utilisation_worst;
    if (rig && loop_s > 0.0) {
      load = static_cast<double>(busy1[b] - busy0[b]) * 1e-9 / loop_s;
    }
    s.bus_load.emplace_back(rh.buses[b].decl.name, load);
  }
  s.faults = faults.records();
  // The drivers' own text: what stopped the controller, every fault event, each injected fault's.
  s.safe_stop_driver = ctrl.stopDescription();
  for (std::size_t i = 0; i < ctrl.faultEventCount(); ++i) {
    const loop::Controller::FaultEvent& e = ctrl.faultEvent(i);
    char at[64];
    std::snprintf(at, sizeof at, "t = %.4f s (cycle %llu) ", static_cast<double>(e.t) * 1e-9,
                  static_cast<unsigned long long>(e.cycle));
    s.fault_events.push_back(at + *e.where + ": " + loop::Controller::describe(e));
  }
  for (const loop::FaultRecord& r : s.faults) {
    std::string on_device;
    for (std::size_t i = 0; i < ctrl.faultEventCount(); ++i) {
      const loop::Controller::FaultEvent& e = ctrl.faultEvent(i);
      if (*e.where != r.device || r.injected_at_s < 0.0 ||
          static_cast<double>(e.t) * 1e-9 + 1e-9 < r.injected_at_s)
        continue;
      on_device += (on_device.empty() ? "" : "; ") + loop::Controller::describe(e);
    }
    s.fault_driver_text.push_back(on_device);
  }
  s.safe_exit_done = exited.done;
  s.safe_exit_cycles = exited.cycles;
  if (!run::writeFaultLog(s, o.out + "/faults.log"))
    throw std::runtime_error(o.out + "/faults.log: cannot write");
#ifdef MRQP_RUN_HAVE_COLLISION
  if (watch.enabled()) {
    s.min_distance_m = watch.minDistance();
    s.delta_s_m = watch.securityDistance();
  }
#endif
  s.extra_fields = pen_watch.summaryFields();
  const std::vector<run::HandSummary> hand_summary = hands.summary();
  if (!hand_summary.empty()) s.extra_fields.emplace_back("hands", run::handsJson(hand_summary));
  if (!run::writeSummaryJson(s, o.out + "/summary.json"))
    throw std::runtime_error(o.out + "/summary.json: cannot write");
  if (!estimator_run.appendSummary(o.out + "/summary.json"))
    throw std::runtime_error(o.out + "/summary.json: cannot add the estimation's fields");
  if (carry && carry->enabled() &&
      !run::appendSummaryFields(o.out + "/summary.json",
                                carry->summaryFields(o.force_control && admittance.size() > 0)))
    throw std::runtime_error(o.out + "/summary.json: cannot write");
  run::printSummary(s);
  run::printHands(hand_summary);
  estimator_run.printSummary();
  for (const std::string& f : pen_watch.write(o.out, o.plots, nullptr))
    std::printf("mrqp-run: wrote %s\n", f.c_str());
  if (o.plots) {
    std::string err;
    std::vector<std::string> pngs = run::writePlots(o.out, ring.columns(), o.scene, &err);
    for (const std::string& f : estimator_run.writePlots(o.out, ring.columns(), &err)) pngs.push_back(f);
    if (carry) {
      std::string carry_err;
      for (const std::string& f : carry->write(o.out, o.scene, &carry_err)) pngs.push_back(f);
      if (!carry_err.empty()) std::fprintf(stderr, "mrqp-run: plots: %s\n", carry_err.c_str());
    }
    if (!err.empty()) std::fprintf(stderr, "mrqp-run: plots: %s\n", err.c_str());
    if (!o.quiet) {
      for (const std::string& f : pngs) std::printf("mrqp-run: plot %s\n", f.c_str());
    }
  }
  if (!hands.empty()) {
    std::string err;
    const std::vector<std::string> files = hands.write(o.out, o.scene, o.plots, &err);
    if (!err.empty()) std::fprintf(stderr, "mrqp-run: force plots: %s\n", err.c_str());
    if (!o.quiet) {
      for (const std::string& f : files) std::printf("mrqp-run: force %s\n", f.c_str());
    }
  }
  if (o.plots) {
    try {
      const std::string what = motion.render(spec, text, o.scene, models, o.out);
      if (!o.quiet) std::printf("mrqp-run: motion %s\n", what.c_str());
    } catch (const std::exception& e) {
      std::fprintf(stderr, "mrqp-run: motion: %s (no rendering)\n", e.what());
    }
  }
  std::printf("mrqp-run: wrote %s/summary.json and %s/log.csv\n", o.out.c_str(), o.out.c_str());
  const bool unexplained_stop = ctrl.safeStopped() && o.faults.empty();
  return unexplained_stop ? 3 : 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return runMain(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "mrqp-run: %s\n", e.what());
  } catch (...) {
    std::fprintf(stderr, "mrqp-run: unknown error\n");
  }
  return 1;
}
