// mrqp-run's record of the force control (see hands_recorder.hpp).
#include "hands_recorder.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

namespace mrqp::run {

HandsRecorder::HandsRecorder(const force::AdmittanceHook& hook, const problem::MultiRobotProblem& p,
                             const loop::Plant* plant, long cycles, double dt)
    : hook_(hook), plant_(plant), dt_(dt), settle_cycles_(std::lround(kSettleS / dt)) {
  const auto n = static_cast<std::size_t>(std::max(0L, cycles));
  // Each end-effector's ancestors: the joints whose column of its sensor frame's Jacobian is not
  // zero. Its chain: those that are no other end-effector's ancestors (JVRC-1's two arms without
  // the waist they share), each with a finite effort limit and a joint of the plant.
  std::vector<std::vector<bool>> ancestors;
  for (int i = 0; i < hook.size(); ++i) {
    const force::EndEffectorSpec& s = hook.spec(i);
    const problem::Entity& e = p.entity(s.entity);
    Eigen::MatrixXd J = Eigen::MatrixXd::Zero(6, e.nv());
    e.frameJacobian(s.sensor_frame, Eigen::Vector3d::Zero(), J);
    std::vector<bool> a(static_cast<std::size_t>(e.nv()), false);
    for (int k = e.jointOffset(); k < e.nv(); ++k) a[static_cast<std::size_t>(k)] = J.col(k).norm() > 0.0;
    ancestors.push_back(std::move(a));
  }
  for (int i = 0; i < hook.size(); ++i) {
    const force::EndEffectorSpec& s = hook.spec(i);
    const problem::Entity& e = p.entity(s.entity);
    Hand h;
    h.name = s.name;
    for (int k = e.jointOffset(); k < e.nv(); ++k) {
      const auto kk = static_cast<std::size_t>(k);
      bool mine = ancestors[static_cast<std::size_t>(i)][kk];
      for (int o = 0; o < hook.size(); ++o) {
        if (o != i && hook.spec(o).entity == s.entity && ancestors[static_cast<std::size_t>(o)][kk])
          mine = false;
      }
      const double limit = e.effortLimit()(k);
      if (!mine || !(limit > 0.0) || !std::isfinite(limit)) continue;
      const int pj = plant != nullptr ? plant->jointHandle(e.name(), e.jointName(k - e.jointOffset())) : -1;
      if (pj >= 0) h.chain.push_back(Joint{pj, limit});
    }
    for (auto* v : {&h.fd, &h.target, &h.measured, &h.velocity, &h.ratio}) v->assign(n, 0.0);
    for (auto* v : {&h.hit, &h.counted, &h.mode}) v->assign(n, 0);
    hands_.push_back(std::move(h));
  }
}

void HandsRecorder::sample(long k) noexcept {
  if (k < 0 || static_cast<std::size_t>(k) >= (hands_.empty() ? 0u : hands_[0].fd.size())) return;
  const auto i = static_cast<std::size_t>(k);
  for (std::size_t h = 0; h < hands_.size(); ++h) {
    Hand& d = hands_[h];
    const force::AdmittanceHook::State& st = hook_.state(static_cast<int>(h));
    const int mode = static_cast<int>(st.mode);
    if (mode != d.last_mode || st.force != d.last_fd) {
      d.changed_at = d.last_mode < 0 ? 0 : k;
      d.last_mode = mode;
      d.last_fd = st.force;
    }
    d.fd[i] = st.force;
    d.target[i] = st.target;
    d.measured[i] = st.measured;
    d.velocity[i] = st.velocity;
    d.mode[i] = static_cast<unsigned char>(mode);
    d.counted[i] =
        st.mode != force::ForceMode::Off && k >= settle_cycles_ && k - d.changed_at >= settle_cycles_;
    double ratio = 0.0;
    if (plant_ != nullptr) {
      for (const Joint& j : d.chain)
        ratio = std::max(ratio, std::abs(plant_->jointTorque(j.plant_joint)) / j.limit);
    }
    d.ratio[i] = ratio;
    d.hit[i] = ratio >= 1.0 - kLimitTolerance;
  }
  samples_ = std::max(samples_, k + 1);
}

std::vector<HandSummary> HandsRecorder::summary() const {
  std::vector<HandSummary> out;
  for (std::size_t h = 0; h < hands_.size(); ++h) {
    const Hand& d = hands_[h];
    const force::AdmittanceHook::State& st = hook_.state(static_cast<int>(h));
    HandSummary s;
    s.name = d.name;
    s.mode = force::forceModeName(st.mode);
    s.force_target_n = st.force;
    s.target_final_n = st.target;
    s.measured_final_n = st.measured;
    double sum = 0.0;
    for (long k = 0; k < samples_; ++k) {
      const auto i = static_cast<std::size_t>(k);
      if (d.counted[i] != 0u) {
        const double e = d.target[i] - d.measured[i];
        sum += e * e;
        ++s.evaluated_cycles;
      }
      if (d.hit[i] != 0u) ++s.torque_limit_hits;
      s.torque_ratio_max = std::max(s.torque_ratio_max, d.ratio[i]);
    }
    s.force_rms_error_n = s.evaluated_cycles > 0 ? std::sqrt(sum / static_cast<double>(s.evaluated_cycles))
                                                 : std::numeric_limits<double>::quiet_NaN();
    if (plant_ == nullptr) {
      s.torque_limit_hits = -1;
      s.torque_ratio_max = std::numeric_limits<double>::quiet_NaN();
    }
    out.push_back(s);
  }
  return out;
}

std::vector<std::string> HandsRecorder::write(const std::string& dir, const std::string& title, bool plots,
                                              std::string* error) const {
  std::vector<std::string> written;
  if (hands_.empty()) return written;
  const std::string csv = dir + "/force.csv";
  FILE* f = std::fopen(csv.c_str(), "w");
  if (f == nullptr) {
    *error = csv + ": cannot write";
    return written;
  }
  std::fprintf(f, "t");
  for (const Hand& d : hands_) {
    const char* n = d.name.c_str();
    std::fprintf(f, ",%s_fd,%s_target,%s_measured,%s_velocity,%s_torque_ratio,%s_mode", n, n, n, n, n, n);
  }
  std::fprintf(f, "\n");
  for (long k = 0; k < samples_; ++k) {
    const auto i = static_cast<std::size_t>(k);
    std::fprintf(f, "%.4f", static_cast<double>(k) * dt_);
    for (const Hand& d : hands_) {
      std::fprintf(f, ",%.6g,%.6g,%.6g,%.6g,%.6g,%d", d.fd[i], d.target[i], d.measured[i], d.velocity[i],
                   d.ratio[i], static_cast<int>(d.mode[i]));
    }
    std::fprintf(f, "\n");
  }
  if (std::fclose(f) != 0) {
    *error = csv + ": cannot write";
    return written;
  }
  written.push_back(csv);
  if (!plots) return written;

  auto gnuplot = [&](const std::string& png, const std::string& script) {
    FILE* gp = popen("gnuplot", "w");
    if (gp == nullptr) {
      *error = "cannot run gnuplot";
      return;
    }
    std::fprintf(gp,
                 "set terminal pngcairo size 1000,%d font ',10' noenhanced\nset output '%s/%s'\n"
                 "set datafile separator ','\nset key outside right\n%s\n",
                 350 * static_cast<int>(hands_.size()) + 50, dir.c_str(), png.c_str(), script.c_str());
    if (pclose(gp) == 0) {
      written.push_back(dir + "/" + png);
    } else {
      *error = "gnuplot failed on " + png;
    }
  };
  // One row per end-effector (Fig. 7): fᵈ, the admittance's target and the sensed force.
  std::string plot = "set multiplot layout " + std::to_string(hands_.size()) + ",1 title '" + title + "'\n";
  std::string limits = plot;
  for (std::size_t h = 0; h < hands_.size(); ++h) {
    const int c = 2 + 6 * static_cast<int>(h);  // gnuplot's columns count from 1; t is 1
    const std::string& n = hands_[h].name;
    const std::string mode = force::forceModeName(static_cast<force::ForceMode>(hands_[h].mode.back()));
    plot += "set title '" + n + " (mode " + mode +
            ")'\nset xlabel 't (s)'\nset ylabel 'force along n (N)'\nplot '" + csv +
            "' every ::1 using 1:" + std::to_string(c) + " with lines dt 2 lw 2 title 'f^d (user)', '" + csv +
            "' every ::1 using 1:" + std::to_string(c + 1) + " with lines lw 2 title 'target', '" + csv +
            "' every ::1 using 1:" + std::to_string(c + 2) + " with lines title 'sensed'\n";
    limits += "set title '" + n +
              ": largest |tau| / tau_max of its chain'\nset xlabel 't (s)'\nset ylabel "
              "'|tau| / tau_max'\nset yrange [0:*]\nplot '" +
              csv + "' every ::1 using 1:" + std::to_string(c + 4) +
              " with lines lw 2 title 'chain', 1 with lines dt 2 lc rgb 'red' title 'limit'\n";
  }
  gnuplot("force_tracking.png", plot + "unset multiplot\n");
  if (plant_ != nullptr) gnuplot("torque_limits.png", limits + "unset multiplot\n");
  return written;
}

}  // namespace mrqp::run
