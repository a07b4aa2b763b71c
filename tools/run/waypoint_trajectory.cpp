// The `trajectories:` section and its reference (see waypoint_trajectory.hpp).
#include "waypoint_trajectory.hpp"

#include <algorithm>
#include <cstring>

#include "problem/tasks/frame_task.hpp"
#include "scene/yaml_reader.hpp"

namespace mrqp::run {

Eigen::Vector3d minimumJerk(double tau) noexcept {
  const double t = std::clamp(tau, 0.0, 1.0);
  const double t2 = t * t, t3 = t2 * t;
  return {t3 * (10.0 - 15.0 * t + 6.0 * t2), 30.0 * t2 * (1.0 - 2.0 * t + t2),
          60.0 * t * (1.0 - 3.0 * t + 2.0 * t2)};
}

namespace {

/// The frame task `name` with linear rows (frame_position or frame_pose): its id.
int linearFrameTask(const scene::Reader& r, const YAML::Node& at, const std::string& field,
                    const scene::Scene& sc, const std::string& name) {
  const auto it = sc.tasks.find(name);
  if (it == sc.tasks.end()) r.fail(at, field, "unknown task '" + name + "' (or not active at the start)");
  const problem::Task& t = sc.problem->task(it->second);
  const bool linear =
      std::strcmp(t.kind(), "frame_position") == 0 || std::strcmp(t.kind(), "frame_pose") == 0;
  if (!linear || dynamic_cast<const problem::FrameTask*>(&t) == nullptr) {
    r.fail(at, field,
           "task '" + name + "' is a " + t.kind() + " task: expected frame_position or frame_pose");
  }
  return it->second;
}

Eigen::Vector3d initialTarget(const scene::Scene& sc, int id) {
  return static_cast<const problem::FrameTask&>(sc.problem->task(id)).target();
}

}  // namespace

WaypointTrajectory WaypointTrajectory::read(const std::string& text, const std::string& file,
                                            const scene::Scene& sc) {
  WaypointTrajectory tr;
  const YAML::Node doc = scene::parseYamlDocument(text, file);
  if (!doc.IsMap() || !doc["trajectories"] || doc["trajectories"].IsNull()) return tr;
  const scene::Reader r(file);
  const std::vector<YAML::Node> items = r.list(doc["trajectories"], "trajectories");
  std::vector<int> used;  // every task moved by some item
  auto claim = [&](const YAML::Node& at, const std::string& field, int id, const std::string& name) {
    if (std::find(used.begin(), used.end(), id) != used.end())
      r.fail(at, field, "task '" + name + "' is already moved by a trajectory");
    used.push_back(id);
  };
  for (std::size_t i = 0; i < items.size(); ++i) {
    const std::string path = scene::item("trajectories", i);
    const scene::Map m(r, items[i], path, {"task", "start", "carry", "waypoints"});
    TrajectorySpec s;
    s.task_name = m.name("task");
    s.task = linearFrameTask(r, *m.find("task"), m.at("task"), sc, s.task_name);
    claim(*m.find("task"), m.at("task"), s.task, s.task_name);
    s.initial = initialTarget(sc, s.task);
    s.start = m.number("start", scene::Bound::NonNegative, 0.0);
    if (const YAML::Node* c = m.find("carry")) {
      const std::vector<std::string> names = r.names(*c, m.at("carry"));
      for (std::size_t k = 0; k < names.size(); ++k) {
        const std::string field = scene::item(m.at("carry"), k);
        const YAML::Node& at = (*c)[k];
        const int id = linearFrameTask(r, at, field, sc, names[k]);
        claim(at, field, id, names[k]);
        s.carried.push_back(id);
        s.carried_initial.push_back(initialTarget(sc, id));
      }
    }
    const std::vector<YAML::Node> wps = r.list(m.require("waypoints"), m.at("waypoints"));
    if (wps.empty()) r.fail(*m.find("waypoints"), m.at("waypoints"), "expected at least one waypoint");
    double last = s.start;
    for (std::size_t k = 0; k < wps.size(); ++k) {
      const std::string wpath = scene::item(m.at("waypoints"), k);
      const scene::Map w(r, wps[k], wpath, {"at", "position"});
      Waypoint p;
      p.at = r.number(w.require("at"), w.at("at"), scene::Bound::NonNegative);
      if (!(p.at > last)) {
        r.fail(
            *w.find("at"), w.at("at"),
            "expected a time after " + scene::formatNumber(last) + " s (the start or the previous waypoint)");
      }
      p.position = r.vec3(w.require("position"), w.at("position"));
      last = p.at;
      s.waypoints.push_back(p);
    }
    tr.items_.push_back(std::move(s));
  }
  return tr;
}

TrajectoryPoint WaypointTrajectory::at(std::size_t i, double t) const noexcept {
  const TrajectorySpec& s = items_[i];
  TrajectoryPoint out;
  out.position = s.initial;
  double t0 = s.start;
  Eigen::Vector3d from = s.initial;
  for (const Waypoint& w : s.waypoints) {
    if (t < w.at) {
      if (t <= t0) return out;  // before the start: the scene's target, at rest
      const double T = w.at - t0;
      const Eigen::Vector3d sj = minimumJerk((t - t0) / T);
      const Eigen::Vector3d d = w.position - from;
      out.position = from + d * sj(0);
      out.velocity = d * (sj(1) / T);
      out.acceleration = d * (sj(2) / (T * T));
      return out;
    }
    t0 = w.at;
    from = w.position;
    out.position = from;
  }
  return out;  // after the last waypoint: there, at rest
}

void WaypointTrajectory::apply(problem::MultiRobotProblem& p, double t) const noexcept {
  for (std::size_t i = 0; i < items_.size(); ++i) {
    const TrajectorySpec& s = items_[i];
    const TrajectoryPoint g = at(i, t);
    auto write = [&](int id, const Eigen::Vector3d& target) noexcept {
      if (!p.taskActive(id)) return;
      if (p.task(id).referenceRows() == 3) {
        (void)p.setTaskReference(id, target, g.velocity, g.acceleration);
        return;
      }
      Eigen::Matrix<double, 6, 1> vel = Eigen::Matrix<double, 6, 1>::Zero();  // angular rows first: at rest
      Eigen::Matrix<double, 6, 1> acc = Eigen::Matrix<double, 6, 1>::Zero();
      vel.tail<3>() = g.velocity;
      acc.tail<3>() = g.acceleration;
      (void)p.setTaskTarget(id, target);
      (void)p.setTaskReference(id, vel, acc);
    };
    write(s.task, g.position);
    const Eigen::Vector3d shift = g.position - s.initial;
    for (std::size_t k = 0; k < s.carried.size(); ++k) write(s.carried[k], s.carried_initial[k] + shift);
  }
}

void WaypointTrajectory::onCycle(loop::Controller& c, drivers::TimeNs) noexcept {
  apply(c.problem(), static_cast<double>(c.cycles()) * c.period());
}

}  // namespace mrqp::run
