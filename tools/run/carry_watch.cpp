// What a carrying scene did to its object (see carry_watch.hpp).
#include "carry_watch.hpp"
#include "summary_fields.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "problem/rigid_object.hpp"
#include "problem/tasks/frame_task.hpp"

namespace mrqp::run {

CarryWatch::CarryWatch(const scene::Scene& model, problem::MultiRobotProblem& shadow,
                       const loop::Plant& plant, const WaypointTrajectory& trajectory,
                       const force::AdmittanceHook* admittance, double duration, double every)
    : shadow_(shadow),
      plant_(plant),
      trajectory_(trajectory),
      admittance_(admittance),
      end_effectors_(admittance != nullptr ? admittance->size() : 0),
      every_(every) {
  if (trajectory.empty()) return;
  const problem::MultiRobotProblem& p = *model.problem;
  const auto& task = static_cast<const problem::FrameTask&>(p.task(trajectory.items()[0].task));
  if (dynamic_cast<const problem::RigidObject*>(&p.entity(task.entity())) == nullptr) return;
  object_ = task.entity();
  object_frame_ = task.frame();
  for (int i = 0; i < p.entityCount(); ++i) plant_handle_.push_back(plant.entityHandle(p.entity(i).name()));
  plant_object_ = plant_handle_[static_cast<std::size_t>(object_)];
  if (plant_object_ < 0) {
    object_ = -1;
    return;
  }
  for (const auto& [name, id] : model.contacts) {
    const problem::ContactDesc& c = p.contact(id);
    Hand h;
    h.name = name;
    if (c.entity == object_ && c.other_entity >= 0 && c.other_entity != object_) {
      h.entity = c.other_entity;
      h.frame = c.other_frame;
    } else if (c.other_entity == object_ && c.entity != object_) {
      h.entity = c.entity;
      h.frame = c.frame;
    } else {
      continue;
    }
    hands_.push_back(h);
  }
  waypoint_error_.assign(trajectory.items()[0].waypoints.size(), std::numeric_limits<double>::quiet_NaN());
  // t, reference xyz, object xyz, each hand's xyz, each end-effector's target and measured force.
  columns_ = 7 + 3 * static_cast<int>(hands_.size()) + 2 * end_effectors_;
  series_.reserve(static_cast<std::size_t>((duration / every + 2.0) * columns_));
}

void CarryWatch::plantState(int entity) {
  problem::Entity& e = shadow_.entity(entity);
  const int h = plant_handle_[static_cast<std::size_t>(entity)];
  if (h >= 0) plant_.entityState(h, e.q(), e.v());
  e.update();
}

void CarryWatch::sample(double t) {
  if (!enabled()) return;
  const TrajectorySpec& tr = trajectory_.items()[0];
  bool due = first_ || t + 1e-9 >= next_;
  for (std::size_t k = 0; k < tr.waypoints.size(); ++k) {
    if (std::isnan(waypoint_error_[k]) && t + 1e-9 >= tr.waypoints[k].at) due = true;
  }
  if (!due) return;
  plantState(object_);
  for (const Hand& h : hands_) plantState(h.entity);
  const Eigen::Vector3d box = shadow_.entity(object_).framePose(object_frame_).p;
  const TrajectoryPoint ref = trajectory_.at(0, t);

  for (std::size_t k = 0; k < tr.waypoints.size(); ++k) {
    if (std::isnan(waypoint_error_[k]) && t + 1e-9 >= tr.waypoints[k].at)
      waypoint_error_[k] = (box - tr.waypoints[k].position).norm();
  }
  if (t >= tr.start && box.z() < ref.position.z() - kDropMargin) dropped_ = true;
  for (Hand& h : hands_) {
    const problem::Pose f = shadow_.entity(h.entity).framePose(h.frame);
    const Eigen::Vector3d rel = f.R.transpose() * (box - f.p);
    if (first_) h.rel0 = rel;
    slip_ = std::max(slip_, (rel - h.rel0).norm());
  }
  first_ = false;
  if (t + 1e-9 < next_) return;  // a waypoint's own time between two samples of the series
  next_ += every_;
  if (series_.size() + static_cast<std::size_t>(columns_) > series_.capacity()) return;
  series_.push_back(t);
  for (int i = 0; i < 3; ++i) series_.push_back(ref.position(i));
  for (int i = 0; i < 3; ++i) series_.push_back(box(i));
  for (const Hand& h : hands_) {
    const Eigen::Vector3d p = shadow_.entity(h.entity).framePose(h.frame).p;
    for (int i = 0; i < 3; ++i) series_.push_back(p(i));
  }
  for (int i = 0; i < end_effectors_; ++i) {
    series_.push_back(admittance_->state(i).target);
    series_.push_back(admittance_->state(i).measured);
  }
}

std::vector<std::pair<std::string, std::string>> CarryWatch::summaryFields(bool force_control) const {
  std::vector<std::pair<std::string, std::string>> out;
  out.emplace_back("force_control", force_control ? "true" : "false");
  if (!enabled()) return out;
  std::string errors = "[";
  for (std::size_t k = 0; k < waypoint_error_.size(); ++k)
    errors += (k ? ", " : "") + jsonNumber(waypoint_error_[k]);
  out.emplace_back("box_waypoint_errors_m", errors + "]");
  out.emplace_back("box_slip_m", jsonNumber(slip_));
  out.emplace_back("box_dropped", dropped_ ? "true" : "false");
  return out;
}

std::vector<std::string> CarryWatch::write(const std::string& dir, const std::string& title,
                                           std::string* error) const {
  std::vector<std::string> written;
  if (!enabled()) return written;
  const std::string csv = dir + "/carry.csv";
  FILE* f = std::fopen(csv.c_str(), "w");
  if (f == nullptr) {
    *error = csv + ": cannot write";
    return written;
  }
  std::fprintf(f, "t,ref_x,ref_y,ref_z,box_x,box_y,box_z");
  for (const Hand& h : hands_)
    std::fprintf(f, ",%s_x,%s_y,%s_z", h.name.c_str(), h.name.c_str(), h.name.c_str());
  for (int i = 0; i < end_effectors_; ++i) {
    const std::string& n = admittance_->spec(i).name;
    std::fprintf(f, ",%s_target_n,%s_measured_n", n.c_str(), n.c_str());
  }
  std::fprintf(f, "\n");
  const auto cols = static_cast<std::size_t>(columns_);
  for (std::size_t r = 0; r + cols <= series_.size(); r += cols) {
    for (std::size_t c = 0; c < cols; ++c) std::fprintf(f, "%s%.9g", c ? "," : "", series_[r + c]);
    std::fprintf(f, "\n");
  }
  if (std::fclose(f) != 0) {
    *error = csv + ": cannot write";
    return written;
  }
  written.push_back(csv);

  // The waypoints as points at their times, for the plot.
  const std::string wp = dir + "/carry_waypoints.csv";
  FILE* w = std::fopen(wp.c_str(), "w");
  if (w == nullptr) {
    *error = wp + ": cannot write";
    return written;
  }
  std::fprintf(w, "t,x,y,z\n");
  for (const Waypoint& p : trajectory_.items()[0].waypoints)
    std::fprintf(w, "%.9g,%.9g,%.9g,%.9g\n", p.at, p.position.x(), p.position.y(), p.position.z());
  std::fclose(w);

  FILE* gp = popen("gnuplot", "w");
  if (gp == nullptr) {
    *error = "cannot run gnuplot";
    return written;
  }
  const char* axis[3] = {"x", "y", "z"};
  std::string s =
      "set terminal pngcairo size 1000,1100 font ',10' noenhanced\nset output '" + dir +
      "/carry_box.png'\nset datafile separator ','\nset key outside right\nset multiplot layout 4,1 title '" +
      title + "'\nset xlabel 't (s)'\n";
  for (int a = 0; a < 3; ++a) {
    s += "set ylabel '" + std::string(axis[a]) + " (m)'\nplot '" + csv +
         "' every ::1 using 1:" + std::to_string(5 + a) + " with lines lw 2 title 'box (plant)', '" + csv +
         "' every ::1 using 1:" + std::to_string(2 + a) + " with lines dt 2 lw 2 title 'box reference', '" +
         wp + "' every ::1 using 1:" + std::to_string(2 + a) + " with points pt 7 ps 1.5 title 'waypoints'";
    for (std::size_t h = 0; h < hands_.size(); ++h) {
      s += ", '" + csv + "' every ::1 using 1:" + std::to_string(8 + 3 * static_cast<int>(h) + a) +
           " with lines title '" + hands_[h].name + "'";
    }
    s += "\n";
  }
  s += "set ylabel 'force along n (N)'\n";
  if (end_effectors_ == 0) {
    s += "plot 0 title 'no force control section'\n";
  } else {
    s += "plot ";
    const int base = 8 + 3 * static_cast<int>(hands_.size());
    for (int i = 0; i < end_effectors_; ++i) {
      const std::string& n = admittance_->spec(i).name;
      s += std::string(i ? ", " : "") + "'" + csv + "' every ::1 using 1:" + std::to_string(base + 2 * i) +
           " with lines dt 2 title '" + n + " target', '" + csv +
           "' every ::1 using 1:" + std::to_string(base + 2 * i + 1) + " with lines lw 2 title '" + n +
           " measured'";
    }
    s += "\n";
  }
  s += "unset multiplot\n";
  std::fputs(s.c_str(), gp);
  if (pclose(gp) == 0) {
    written.push_back(dir + "/carry_box.png");
  } else {
    *error = "gnuplot failed on carry_box.png";
  }
  return written;
}

}  // namespace mrqp::run
