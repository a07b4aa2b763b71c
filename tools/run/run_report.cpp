// mrqp-run's results (see run_report.hpp).
#include "run_report.hpp"
#include "summary_fields.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace mrqp::run {

double percentile(const std::vector<double>& sorted, double p) {
  if (sorted.empty()) return 0.0;
  const double rank = std::ceil(p * static_cast<double>(sorted.size()));
  const std::size_t i =
      static_cast<std::size_t>(std::clamp(rank, 1.0, static_cast<double>(sorted.size()))) - 1;
  return sorted[i];
}

namespace {

std::string time(double v) { return v < 0.0 ? "null" : jsonNumber(v); }

std::string object(const std::vector<std::pair<std::string, double>>& kv) {
  std::string out = "{";
  for (std::size_t i = 0; i < kv.size(); ++i) {
    out += (i ? ", " : "") + jsonString(kv[i].first) + ": " + jsonNumber(kv[i].second);
  }
  return out + "}";
}

}  // namespace

bool writeSummaryJson(const RunSummary& s, const std::string& path) {
  FILE* f = std::fopen(path.c_str(), "w");
  if (f == nullptr) return false;
  std::string faults = "[";
  for (std::size_t i = 0; i < s.faults.size(); ++i) {
    const loop::FaultRecord& r = s.faults[i];
    faults += std::string(i ? "," : "") + "\n    {\"kind\": " + jsonString(r.kind) +
              ", \"device\": " + jsonString(r.device) + ", \"injected_at_s\": " + time(r.injected_at_s) +
              ", \"detected_at_s\": " + time(r.detected_at_s) +
              ", \"safe_state_at_s\": " + time(r.safe_state_at_s) + ", \"driver\": " +
              (i < s.fault_driver_text.size() && !s.fault_driver_text[i].empty()
                   ? jsonString(s.fault_driver_text[i])
                   : std::string("null")) +
              "}";
  }
  faults += s.faults.empty() ? "]" : "\n  ]";
  std::string events = "[";
  for (std::size_t i = 0; i < s.fault_events.size(); ++i) {
    events += std::string(i ? "," : "") + "\n    " + jsonString(s.fault_events[i]);
  }
  events += s.fault_events.empty() ? "]" : "\n  ]";
  const std::string safety =
      ",\n  \"safe_stop_driver\": " +
      (s.safe_stop_driver.empty() ? std::string("null") : jsonString(s.safe_stop_driver)) +
      ",\n  \"fault_events\": " + events +
      ",\n  \"safe_exit\": {\"done\": " + (s.safe_exit_done ? "true" : "false") +
      ", \"cycles\": " + std::to_string(s.safe_exit_cycles) + "}";
  const std::string collision = std::isfinite(s.min_distance_m)
                                    ? ",\n  \"min_distance_m\": " + jsonNumber(s.min_distance_m) +
                                          ",\n  \"delta_s_m\": " + jsonNumber(s.delta_s_m)
                                    : std::string();
  std::string extra;  // a scene's own fields (e.g. pen_click_watch.hpp), after the common ones
  for (const auto& [name, value] : s.extra_fields) extra += ",\n  " + jsonString(name) + ": " + value;
  std::fprintf(f,
               "{\n  \"scene\": %s,\n  \"cycles\": %ld,\n  \"period_s\": %s,\n  \"deadline_misses\": %ld,\n"
               "  \"allocations_in_loop\": %ld,\n  \"log_records_dropped\": %ld,\n"
               "  \"cycle_time_us\": {\"median\": %s, \"p99\": %s, \"p999\": %s, \"max\": %s},\n"
               "  \"safe_stop\": %s,\n  \"task_errors_final\": %s,\n  \"joint_tracking_error_max_rad\": %s,\n"
               "  \"base_estimate_error_m\": %s,\n  \"bus_load\": %s,\n  \"faults\": %s%s%s%s\n}\n",
               jsonString(s.scene).c_str(), s.cycles, jsonNumber(s.period_s).c_str(), s.deadline_misses,
               s.allocations_in_loop, s.log_records_dropped, jsonNumber(s.median_us).c_str(),
               jsonNumber(s.p99_us).c_str(), jsonNumber(s.p999_us).c_str(), jsonNumber(s.max_us).c_str(),
               s.safe_stop.empty() ? "null" : jsonString(s.safe_stop).c_str(),
               object(s.task_errors_final).c_str(), object(s.joint_tracking_error_max_rad).c_str(),
               object(s.base_estimate_error_m).c_str(), object(s.bus_load).c_str(), faults.c_str(),
               safety.c_str(), collision.c_str(), extra.c_str());
  return std::fclose(f) == 0;
}

bool writeFaultLog(const RunSummary& s, const std::string& path) {
  FILE* f = std::fopen(path.c_str(), "w");
  if (f == nullptr) return false;
  for (const std::string& e : s.fault_events) std::fprintf(f, "%s\n", e.c_str());
  return std::fclose(f) == 0;
}

void printSummary(const RunSummary& s) {
  std::printf("mrqp-run: %ld cycles of %.3g ms\n", s.cycles, s.period_s * 1e3);
  std::printf("  final task errors:\n");
  for (const auto& [name, v] : s.task_errors_final) std::printf("    %-20s %.3g\n", name.c_str(), v);
  std::printf("  cycle time (µs): median %.1f, p99 %.1f, p99.9 %.1f, max %.1f; deadline misses %ld\n",
              s.median_us, s.p99_us, s.p999_us, s.max_us, s.deadline_misses);
  for (const auto& [name, v] : s.joint_tracking_error_max_rad) {
    std::printf("  %s: joint tracking error max %.3g rad\n", name.c_str(), v);
  }
  for (const auto& [name, v] : s.base_estimate_error_m)
    std::printf("  %s: base estimate error %.3g m\n", name.c_str(), v);
  for (const auto& [name, v] : s.bus_load) std::printf("  bus %s: load %.1f %%\n", name.c_str(), v * 100.0);
  std::printf("  allocations in the loop: %ld; log records dropped: %ld\n", s.allocations_in_loop,
              s.log_records_dropped);
  std::printf("  safe stop: %s\n", s.safe_stop.empty() ? "none" : s.safe_stop.c_str());
  if (!s.safe_stop_driver.empty()) std::printf("    %s\n", s.safe_stop_driver.c_str());
  for (const std::string& e : s.fault_events) std::printf("  fault event %s\n", e.c_str());
  std::printf("  safe exit: %s after %ld cycles\n", s.safe_exit_done ? "drives stopped" : "NOT completed",
              s.safe_exit_cycles);
  for (const loop::FaultRecord& r : s.faults) {
    std::printf("  fault %s on %s: injected %s s, detected %s s, safe state %s s\n", r.kind.c_str(),
                r.device.c_str(), time(r.injected_at_s).c_str(), time(r.detected_at_s).c_str(),
                time(r.safe_state_at_s).c_str());
  }
}

std::vector<std::string> writePlots(const std::string& dir, const std::vector<std::string>& columns,
                                    const std::string& title, std::string* error) {
  std::vector<std::string> written;
  const std::string csv = dir + "/log.csv";
  auto cols = [&](const std::string& prefix) {
    std::vector<int> out;
    for (std::size_t i = 0; i < columns.size(); ++i) {
      if (columns[i].compare(0, prefix.size(), prefix) == 0) out.push_back(static_cast<int>(i) + 1);
    }
    return out;
  };
  auto run = [&](const std::string& png, const std::string& script) {
    FILE* gp = popen("gnuplot", "w");
    if (gp == nullptr) {
      *error = "cannot run gnuplot";
      return;
    }
    std::fprintf(gp,
                 "set terminal pngcairo size 1000,600 font ',10' noenhanced\nset output '%s/%s'\n"
                 "set datafile separator ','\nset key outside right\nset title '%s'\n%s\n",
                 dir.c_str(), png.c_str(), title.c_str(), script.c_str());
    if (pclose(gp) == 0) {
      written.push_back(dir + "/" + png);
    } else {
      *error = "gnuplot failed on " + png;
    }
  };
  std::string plot;
  const std::vector<int> tasks = cols("err_");
  if (!tasks.empty()) {
    plot = "set logscale y\nset xlabel 't (s)'\nset ylabel 'task error'\nplot ";
    for (std::size_t i = 0; i < tasks.size(); ++i) {
      plot += (i ? ", " : "") + std::string("'") + csv + "' every ::1 using 1:(column(" +
              std::to_string(tasks[i]) + ") > 0 ? column(" + std::to_string(tasks[i]) +
              ") : 1/0) with lines lw 2 title columnhead(" + std::to_string(tasks[i]) + ")";
    }
    run("task_errors.png", plot);
  }
  const std::vector<int> forces = cols("fx_");
  if (!forces.empty()) {
    plot = "set xlabel 't (s)'\nset ylabel 'contact force (N)'\nplot ";
    for (std::size_t i = 0; i < forces.size(); ++i) {
      const int c = forces[i];
      plot += (i ? ", " : "") + std::string("'") + csv + "' every ::1 using 1:(sqrt(column(" +
              std::to_string(c) + ")**2 + column(" + std::to_string(c + 1) + ")**2 + column(" +
              std::to_string(c + 2) + ")**2)) with lines title columnhead(" + std::to_string(c) + ")";
    }
    run("contact_forces.png", plot);
  }
  const std::vector<int> cmd = cols("cmd_");
  if (!cmd.empty()) {
    plot = "set xlabel 't (s)'\nset ylabel 'joint position (rad)'\nplot ";
    const std::size_t n = std::min<std::size_t>(cmd.size(), 4);
    for (std::size_t i = 0; i < n; ++i) {
      const int c = cmd[i];
      plot += (i ? ", " : "") + std::string("'") + csv + "' every ::1 using 1:" + std::to_string(c) +
              " with lines lw 2 title columnhead(" + std::to_string(c) + "), '" + csv +
              "' every ::1 using 1:" + std::to_string(c + 1) + " with lines dt 2 title columnhead(" +
              std::to_string(c + 1) + ")";
    }
    run("command_feedback.png", plot);
  }
  const std::vector<int> cycle = cols("cycle_us");
  if (!cycle.empty()) {
    plot =
        "set xlabel 'cycle time (us)'\nset ylabel 'cycles'\nset logscale y\nbin(x) = 5*floor(x/5)\n"
        "set boxwidth 5\nset style fill solid 0.6\nplot '" +
        csv + "' every ::1 using (bin(column(" + std::to_string(cycle[0]) +
        "))):(1) smooth frequency with boxes title 'cycle time'";
    run("cycle_time_histogram.png", plot);
  }
  return written;
}

}  // namespace mrqp::run
