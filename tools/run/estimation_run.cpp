// mrqp-run's part of the estimation section (see estimation_run.hpp).
#include "estimation_run.hpp"
#include "summary_fields.hpp"

#include <cctype>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace mrqp::run {

namespace {

std::string kco(const Eigen::Vector3d& v) {
  return "{\"K\": " + jsonNumber(v(0)) + ", \"C\": " + jsonNumber(v(1)) + ", \"O\": " + jsonNumber(v(2)) +
         "}";
}

int columnOf(const std::vector<std::string>& columns, const std::string& name) {
  for (std::size_t i = 0; i < columns.size(); ++i) {
    if (columns[i] == name) return static_cast<int>(i) + 1;  // gnuplot counts from 1
  }
  return -1;
}

}  // namespace

double convergedAfter(const std::vector<double>& t, const std::vector<double>& v, double truth,
                      double tolerance) {
  const double band = tolerance * std::abs(truth);
  double since = -1.0;
  for (std::size_t k = 0; k < v.size() && k < t.size(); ++k) {
    const bool in = std::isfinite(v[k]) && std::abs(v[k] - truth) <= band;
    if (!in) {
      since = -1.0;
    } else if (since < 0.0) {
      since = t[k];
    }
  }
  return since;
}

EstimationRun::EstimationRun(const estimation::EstimationSpec& spec, loop::Controller& controller,
                             loop::LogRing& log, long cycles)
    : spec_(spec) {
  if (!spec.present || spec.entities.empty()) return;
  hook_ = std::make_unique<estimation::EstimatorHook>(controller, spec);
  if (!controller.addHook(*hook_))
    throw std::runtime_error("estimation: the controller has no room for its hook");
  controller.attachLogValues(log, hook_->logColumns(), hook_->logValues());
  t_.reserve(static_cast<std::size_t>(std::max(0L, cycles)));
  mass_.resize(spec.entities.size());
  for (auto& m : mass_) m.reserve(static_cast<std::size_t>(std::max(0L, cycles)));
}

void EstimationRun::record(double t) {
  if (!hook_) return;
  t_.push_back(t);
  for (int i = 0; i < hook_->size(); ++i) mass_[static_cast<std::size_t>(i)].push_back(hook_->mass(i));
}

std::vector<std::pair<std::string, std::string>> EstimationRun::summaryFields() const {
  std::vector<std::pair<std::string, std::string>> out;
  if (!hook_) return out;
  bool mass_done = false, spring_done = false;
  std::string updates = "{";
  for (int i = 0; i < hook_->size(); ++i) {
    const estimation::EntityEstimationSpec& e = hook_->spec(i);
    updates += std::string(i ? ", " : "") + "\"" + e.name + "\": " + std::to_string(hook_->updates(i));
    if (e.estimate != estimation::BodyEstimate::None && !mass_done) {
      mass_done = true;
      const double t_conv = convergedAfter(t_, mass_[static_cast<std::size_t>(i)], e.true_mass, 0.01);
      out.emplace_back("mass_true_kg", jsonNumber(e.true_mass));
      out.emplace_back("mass_initial_kg", jsonNumber(e.initial_mass));
      out.emplace_back("mass_estimate_kg", jsonNumber(hook_->mass(i)));
      out.emplace_back("mass_std_kg", jsonNumber(hook_->massStd(i)));
      out.emplace_back("mass_converged_s", t_conv < 0.0 ? "null" : jsonNumber(t_conv));
      out.emplace_back("com_estimate_error_m", jsonNumber((hook_->com(i) - e.true_com).norm()));
    }
    if (!e.springs.empty() && !spring_done) {
      spring_done = true;
      out.emplace_back("spring_joint", "\"" + e.name + "." + e.springs.front().joint + "\"");
      out.emplace_back("spring_true", kco(e.springs.front().truth));
      out.emplace_back("spring_initial", kco(e.springs.front().initial));
      out.emplace_back("spring_estimate", kco(hook_->spring(i, 0)));
      out.emplace_back("spring_std", kco(hook_->springStd(i, 0)));
    }
  }
  out.emplace_back("estimation_updates", updates + "}");
  return out;
}

bool EstimationRun::appendSummary(const std::string& path) const {
  const std::vector<std::pair<std::string, std::string>> fields = summaryFields();
  if (fields.empty()) return true;
  std::ifstream in(path);
  if (!in) return false;
  std::stringstream ss;
  ss << in.rdbuf();
  std::string text = ss.str();
  const std::size_t close = text.find_last_of('}');
  if (close == std::string::npos || text.find_first_not_of(" \n\r\t", close + 1) != std::string::npos)
    return false;
  std::size_t end = close;
  while (end > 0 && std::isspace(static_cast<unsigned char>(text[end - 1]))) --end;
  std::string add;
  for (const auto& [name, value] : fields) add += ",\n  \"" + name + "\": " + value;
  text = text.substr(0, end) + add + "\n}\n";
  std::ofstream out(path);
  out << text;
  return static_cast<bool>(out);
}

void EstimationRun::printSummary() const {
  if (!hook_) return;
  for (int i = 0; i < hook_->size(); ++i) {
    const estimation::EntityEstimationSpec& e = hook_->spec(i);
    std::printf("  estimation of %s: %ld updates, NIS of the last %.3g\n", e.name.c_str(), hook_->updates(i),
                hook_->estimator(i).filter().lastNis());
    if (e.estimate != estimation::BodyEstimate::None) {
      std::printf("    mass %.4g kg ± %.2g (2σ), true %.4g kg; CoM error %.3g m\n", hook_->mass(i),
                  2.0 * hook_->massStd(i), e.true_mass, (hook_->com(i) - e.true_com).norm());
      if (e.feed_back)
        std::printf("    fed back into the QP's model; estimates it refused: %ld\n", hook_->feedBackRefused(i));
    }
    for (std::size_t k = 0; k < e.springs.size(); ++k) {
      const Eigen::Vector3d s = hook_->spring(i, static_cast<int>(k));
      const Eigen::Vector3d sd = hook_->springStd(i, static_cast<int>(k));
      const Eigen::Vector3d& t = e.springs[k].truth;
      std::printf(
          "    spring %s: K %.4g ± %.2g (true %.4g), C %.4g ± %.2g (true %.4g), O %.4g ± %.2g (true %.4g)\n",
          e.springs[k].joint.c_str(), s(0), 2.0 * sd(0), t(0), s(1), 2.0 * sd(1), t(1), s(2), 2.0 * sd(2),
          t(2));
    }
  }
}

std::vector<std::string> EstimationRun::writePlots(const std::string& dir,
                                                   const std::vector<std::string>& columns,
                                                   std::string* error) const {
  std::vector<std::string> written;
  if (!hook_) return written;
  const std::string csv = dir + "/log.csv";
  // One panel per estimated quantity: the estimate, its ±2σ band and the truth (Fig. 10).
  struct Panel {
    std::string column, label;
    double truth;
  };
  std::vector<Panel> panels;
  for (int i = 0; i < hook_->size(); ++i) {
    const estimation::EntityEstimationSpec& e = hook_->spec(i);
    const std::string base = "est_" + e.name;
    if (e.estimate != estimation::BodyEstimate::None)
      panels.push_back({base + "_mass", e.name + " mass (kg)", e.true_mass});
    for (const estimation::EstimatedSpringSpec& s : e.springs) {
      panels.push_back({base + "_" + s.joint + "_K", e.name + "." + s.joint + " K (N·m/rad)", s.truth(0)});
      panels.push_back({base + "_" + s.joint + "_C", e.name + "." + s.joint + " C (N·m·s/rad)", s.truth(1)});
      panels.push_back({base + "_" + s.joint + "_O", e.name + "." + s.joint + " O (N·m)", s.truth(2)});
    }
  }
  std::string script;
  char buf[512];
  std::snprintf(
      buf, sizeof buf,
      "set terminal pngcairo size 1000,%d font ',10' noenhanced\nset output '%s/estimation.png'\n"
      "set datafile separator ','\nset multiplot layout %zu,1 title 'estimates with their ±2σ band'\n",
      260 * static_cast<int>(panels.size()) + 40, dir.c_str(), panels.size());
  script += buf;
  for (const Panel& p : panels) {
    const int c = columnOf(columns, p.column), sd = columnOf(columns, p.column + "_std");
    if (c < 0 || sd < 0) continue;
    std::snprintf(
        buf, sizeof buf,
        "set xlabel 't (s)'\nset ylabel '%s'\nplot '%s' every ::1 using 1:(column(%d)-2*column(%d)):"
        "(column(%d)+2*column(%d)) with filledcurves fs transparent solid 0.25 noborder title '±2σ', "
        "'' every ::1 using 1:%d with lines lw 2 title 'estimate', %.9g with lines dt 2 title 'true'\n",
        p.label.c_str(), csv.c_str(), c, sd, c, sd, c, p.truth);
    script += buf;
  }
  script += "unset multiplot\n";
  FILE* gp = popen("gnuplot", "w");
  if (gp == nullptr) {
    *error = "cannot run gnuplot";
    return written;
  }
  std::fputs(script.c_str(), gp);
  if (pclose(gp) == 0) {
    written.push_back(dir + "/estimation.png");
  } else {
    *error = "gnuplot failed on estimation.png";
  }
  return written;
}

}  // namespace mrqp::run
