// summary.json's click-pen fields (see pen_click_watch.hpp).
#include "pen_click_watch.hpp"
#include "summary_fields.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "scene/scene_yaml.hpp"

namespace mrqp::run {

namespace {

std::string where(const scene::Source& s) { return s.file + ":" + std::to_string(s.line); }

}  // namespace

PenClickWatch::PenClickWatch(const scene::SceneSpec& spec, const scene::ModelRegistry& models,
                             const problem::MultiRobotProblem& controller, const loop::Plant& plant,
                             long cycles)
    : controller_(controller), plant_(plant) {
  const scene::EntitySpec* pen = nullptr;
  for (const scene::EntitySpec& e : spec.entities) {
    if (e.model == "pen") {
      pen = &e;
      break;
    }
  }
  if (pen == nullptr) return;
  const scene::ContactSpec* grip = nullptr;
  for (const scene::ContactSpec& c : spec.contacts) {
    if (c.entity == pen->name && !c.other_entity.empty() && c.other_entity != pen->name) {
      grip = &c;
      break;
    }
    if (c.other_entity == pen->name && c.entity != pen->name) {
      grip = &c;
      break;
    }
  }
  if (grip == nullptr) {
    throw scene::SceneError(where(pen->source) + ": entities[" + pen->name +
                            "]: the pen has no contact with a hand (summary.json's pen_slip_m)");
  }
  const bool pen_is_surface = grip->entity == pen->name;
  const std::string hand_name = pen_is_surface ? grip->other_entity : grip->entity;
  const std::string hand_contact_frame = pen_is_surface ? grip->other_frame : grip->frame;

  own_ = scene::buildScene(spec, models);
  problem::MultiRobotProblem& p = *own_.problem;
  const int pen_index = p.entityIndex(pen->name);
  hand_ = p.entityIndex(hand_name);
  const problem::Entity& pe = p.entity(pen_index);
  const int k = pe.jointIndex("button");
  if (k < 0) {
    throw scene::SceneError(where(pen->source) + ": entities[" + pen->name +
                            "]: the pen's model has no joint 'button'");
  }
  button_q_ = pe.qIndexOfV(k);
  travel_required_ = pe.qUpper()(k) - kLatchBeforeStop;
  const problem::Entity& he = p.entity(hand_);
  palm_frame_ = he.frameIndex("palm");
  if (palm_frame_ < 0) palm_frame_ = he.frameIndex(hand_contact_frame);
  pen_handle_ = plant.entityHandle(pen->name);
  hand_handle_ = plant.entityHandle(hand_name);
  pen_q_.resize(pe.nq());
  pen_v_.resize(pe.nv());
  hand_q_.resize(he.nq());
  hand_v_.resize(he.nv());
  const auto n = static_cast<std::size_t>(std::max(0L, cycles));
  t_.assign(n, 0.0);
  travel_.assign(n, 0.0);
  estimate_.assign(n, 0.0);
  slip_.assign(n, 0.0);
  pen_ = pen_index;
}

void PenClickWatch::measure(double t) noexcept {
  if (pen_ < 0 || count_ >= t_.size() || pen_handle_ < 0 || hand_handle_ < 0) return;
  problem::MultiRobotProblem& p = *own_.problem;
  plant_.entityState(pen_handle_, pen_q_, pen_v_);
  plant_.entityState(hand_handle_, hand_q_, hand_v_);
  problem::Entity& pe = p.entity(pen_);
  problem::Entity& he = p.entity(hand_);
  pe.q() = pen_q_;
  pe.v().setZero();
  he.q() = hand_q_;
  he.v().setZero();
  pe.update();
  he.update();
  const problem::Pose palm = he.framePose(palm_frame_);
  const problem::Pose pen = pe.framePose(0);
  const Eigen::Vector3d in_palm = palm.R.transpose() * (pen.p - palm.p);
  if (!have_origin_) {
    origin_in_palm_ = in_palm;
    have_origin_ = true;
  }
  const double travel = pen_q_(button_q_);
  const double slip = (in_palm - origin_in_palm_).norm();
  travel_max_ = std::max(travel_max_, travel);
  slip_max_ = std::max(slip_max_, slip);
  t_[count_] = t;
  travel_[count_] = travel;
  estimate_[count_] = controller_.entity(pen_).q()(button_q_);
  slip_[count_] = slip;
  ++count_;
}

std::vector<std::pair<std::string, std::string>> PenClickWatch::summaryFields() const {
  if (pen_ < 0) return {};
  return {{"button_travel_max_m", jsonNumber(travel_max_)},
          {"button_travel_required_m", jsonNumber(travel_required_)},
          {"pen_slip_m", jsonNumber(slip_max_)}};
}

std::vector<std::string> PenClickWatch::write(const std::string& dir, bool plot, std::string* error) const {
  std::vector<std::string> written;
  if (pen_ < 0) return written;
  const std::string csv = dir + "/button_travel.csv";
  FILE* f = std::fopen(csv.c_str(), "w");
  if (f == nullptr) {
    if (error != nullptr) *error = csv + ": cannot write";
    return written;
  }
  std::fprintf(f, "t,button_travel_m,button_estimate_m,pen_slip_m\n");
  for (std::size_t i = 0; i < count_; ++i) {
    std::fprintf(f, "%.6f,%.9g,%.9g,%.9g\n", t_[i], travel_[i], estimate_[i], slip_[i]);
  }
  if (std::fclose(f) != 0) {
    if (error != nullptr) *error = csv + ": cannot write";
    return written;
  }
  written.push_back(csv);
  if (!plot) return written;
  const std::string png = dir + "/button_travel.png";
  FILE* gp = popen("gnuplot", "w");
  if (gp == nullptr) {
    if (error != nullptr) *error = "gnuplot: cannot run";
    return written;
  }
  std::fprintf(gp,
               "set terminal pngcairo size 900,500\nset output '%s'\nset datafile separator ','\n"
               "set title 'pen click: button travel (required %.2f mm), pen slip in the palm'\n"
               "set xlabel 't (s)'\nset ylabel 'mm'\nset key bottom right\nset grid\n"
               "plot '%s' using 1:($2*1000) every ::1 with lines lw 2 title 'button travel (plant)', "
               "'' using 1:($3*1000) every ::1 with lines dt 2 title 'button travel (controller estimate)', "
               "%.6f with lines lc rgb 'red' dt 3 title 'required for the click', "
               "'' using 1:($4*1000) every ::1 with lines title 'pen slip in the palm'\n",
               png.c_str(), travel_required_ * 1e3, csv.c_str(), travel_required_ * 1e3);
  if (pclose(gp) != 0) {
    if (error != nullptr) *error = "gnuplot failed on " + png;
    return written;
  }
  written.push_back(png);
  return written;
}

}  // namespace mrqp::run
