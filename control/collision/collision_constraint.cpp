// Collision avoidance by velocity dampers between convex shapes (eq. 21, 24) over the loop's
// semi-implicit Euler step; see collision_constraint.hpp.
#include "collision/collision_constraint.hpp"

#include <algorithm>
#include <cmath>

#include "collision/bounding_sphere.hpp"
#include "collision/distance_rate.hpp"
#include "problem/multi_robot_problem.hpp"

namespace mrqp::problem {

CollisionConstraint::CollisionConstraint(std::vector<CollisionBody> bodies, std::vector<CollisionPair> pairs,
                                         int rows, int max_nv,
                                         std::vector<std::shared_ptr<const void>> keep_alive)
    : bodies_(std::move(bodies)),
      pairs_(std::move(pairs)),
      rows_(rows),
      keep_alive_(std::move(keep_alive)),
      placed_(bodies_.size()),
      distance_(pairs_.size(), std::numeric_limits<double>::infinity()),
      result_(pairs_.size()),
      candidates_(pairs_.size()),
      xi_(pairs_.size(), 0.0),
      was_active_(pairs_.size(), 0),
      now_active_(pairs_.size(), 0),
      row_pair_(static_cast<std::size_t>(std::max(0, rows)), -1),
      row_witness_(static_cast<std::size_t>(std::max(0, rows))),
      row_e_(static_cast<std::size_t>(std::max(0, rows)), 0.0),
      row_ddot_(static_cast<std::size_t>(std::max(0, rows)), 0.0),
      row_rate_(static_cast<std::size_t>(std::max(0, rows)), 0.0),
      Ja_(Eigen::MatrixXd::Zero(6, std::max(1, max_nv))),
      Jb_(Eigen::MatrixXd::Zero(6, std::max(1, max_nv))) {}

const char* CollisionConstraint::check(const MultiRobotProblem& p) const noexcept {
  if (rows_ < 1) return "a collision constraint needs at least one row";
  for (const CollisionBody& b : bodies_) {
    if (b.entity < 0 || b.entity >= p.entityCount())
      return "a collision shape names an entity that does not exist";
    const Entity& e = p.entity(b.entity);
    if (b.frame < 0 || b.frame >= e.frameCount())
      return "a collision shape names a frame that does not exist";
    if (e.nv() > Ja_.cols())
      return "a collision constraint's Jacobian work space is smaller than an entity's nv";
    if (b.shape.kind == collision::ShapeKind::Hull && (b.shape.vertices == nullptr || b.shape.nvertices < 1))
      return "a collision hull has no vertices";
  }
  for (const CollisionPair& c : pairs_) {
    if (c.a < 0 || c.b < 0 || c.a >= bodyCount() || c.b >= bodyCount() || c.a == c.b)
      return "a collision pair names a shape that does not exist";
    if (!(c.interaction > c.security) || !(c.security >= 0.0) || !(c.damping > 0.0))
      return "a collision pair needs interaction > security >= 0 and damping > 0";
  }
  return nullptr;
}

collision::PlacedShape CollisionConstraint::placed(const MultiRobotProblem& p, int i) const noexcept {
  const CollisionBody& b = body(i);
  const Pose f = p.entity(b.entity).framePose(b.frame);
  return collision::place(b.shape, f.R, f.p);
}

void CollisionConstraint::update(const MultiRobotProblem& p, ConstraintRows& out) noexcept {
  for (int i = 0; i < bodyCount(); ++i) placed_[static_cast<std::size_t>(i)] = placed(p, i);
  // Distances of the pairs within reach, and the candidates for a row.
  int ncand = 0;
  min_distance_ = std::numeric_limits<double>::infinity();
  for (int k = 0; k < pairCount(); ++k) {
    const auto uk = static_cast<std::size_t>(k);
    const CollisionPair& c = pairs_[uk];
    const collision::PlacedShape& A = placed_[static_cast<std::size_t>(c.a)];
    const collision::PlacedShape& B = placed_[static_cast<std::size_t>(c.b)];
    distance_[uk] = std::numeric_limits<double>::infinity();
    if (collision::boundingDistance(A, body(c.a).bound, B, body(c.b).bound) >= c.interaction) continue;
    collision::distance(A, B, &result_[uk]);
    distance_[uk] = result_[uk].distance;
    min_distance_ = std::min(min_distance_, distance_[uk]);
    if (distance_[uk] < c.interaction) candidates_[static_cast<std::size_t>(ncand++)] = k;
  }
  // The most urgent first: smallest (d − δs)/(δi − δs). Every pair that fits gets its nearest
  // witness's row; the rows left go to the other witnesses of the pairs, in the same order.
  auto urgency = [this](int k) {
    const CollisionPair& c = pairs_[static_cast<std::size_t>(k)];
    return (distance_[static_cast<std::size_t>(k)] - c.security) / (c.interaction - c.security);
  };
  std::sort(candidates_.begin(), candidates_.begin() + ncand, [&](int x, int y) { return urgency(x) < urgency(y); });
  const int n = std::min(ncand, rows_);
  dropped_ = ncand - n;
  dropped_witnesses_ = 0;
  for (int r = 0; r < n; ++r) {
    const int k = candidates_[static_cast<std::size_t>(r)];
    collision::Witness& w = row_witness_[static_cast<std::size_t>(r)];
    w.a = collision::ShapePart{};
    w.b = collision::ShapePart{};
    w.result = result_[static_cast<std::size_t>(k)];
    writeRow(p, r, k, out);
  }
  int used = n;
  for (int i = 0; i < n && used < rows_; ++i) {
    const int k = candidates_[static_cast<std::size_t>(i)];
    const CollisionPair& c = pairs_[static_cast<std::size_t>(k)];
    if (urgency(k) >= kWitnessUrgency) break;  // sorted: the others are farther still
    const int nw = collision::contactWitnesses(placed_[static_cast<std::size_t>(c.a)],
                                               placed_[static_cast<std::size_t>(c.b)],
                                               result_[static_cast<std::size_t>(k)], collision::kWitnessBand,
                                               scratch_.data(), collision::kMaxWitnesses);
    for (int j = 1; j < nw; ++j) {
      if (used == rows_) {
        ++dropped_witnesses_;
        continue;
      }
      row_witness_[static_cast<std::size_t>(used)] = scratch_[static_cast<std::size_t>(j)];
      writeRow(p, used++, k, out);
    }
  }
  active_ = used;
  // A pair entering δi faster than ξ allows gets the damping that its rows' entry speeds need (as
  // Tasks' CollisionConstr does), kept while it stays active: its rows hold at q̈ = 0 then.
  for (int r = 0; r < used; ++r) {
    const auto uk = static_cast<std::size_t>(row_pair_[static_cast<std::size_t>(r)]);
    if (!was_active_[uk] && !now_active_[uk]) xi_[uk] = pairs_[uk].damping;
    now_active_[uk] = 1;
  }
  for (int r = 0; r < used; ++r) {
    const auto ur = static_cast<std::size_t>(r);
    const auto uk = static_cast<std::size_t>(row_pair_[ur]);
    if (was_active_[uk] || !(row_e_[ur] > 0.0)) continue;
    xi_[uk] = std::max(xi_[uk], -row_ddot_[ur] / row_e_[ur] + pairs_[uk].damping);
  }
  // d_{k+1} − d = Δt ḋ + Δt² (g q̈ + ½ D) ≥ −Δt ξ' e (collision_constraint.hpp).
  for (int r = 0; r < used; ++r) {
    const auto ur = static_cast<std::size_t>(r);
    out.l(r) = -xi_[static_cast<std::size_t>(row_pair_[ur])] * row_e_[ur] - row_rate_[ur];
  }
  for (std::size_t k = 0; k < pairs_.size(); ++k) {
    was_active_[k] = now_active_[k];
    now_active_[k] = 0;
  }
}

void CollisionConstraint::writeRow(const MultiRobotProblem& p, int r, int k, ConstraintRows& out) noexcept {
  const auto ur = static_cast<std::size_t>(r);
  const CollisionPair& c = pairs_[static_cast<std::size_t>(k)];
  const collision::DistanceResult& res = row_witness_[ur].result;
  const CollisionBody& ba = body(c.a);
  const CollisionBody& bb = body(c.b);
  const Entity& ea = p.entity(ba.entity);
  const Entity& eb = p.entity(bb.entity);
  const Pose fa = ea.framePose(ba.frame), fb = eb.framePose(bb.frame);
  const Eigen::Vector3d la = fa.R.transpose() * (res.a - fa.p);  // witnesses in frame coordinates
  const Eigen::Vector3d lb = fb.R.transpose() * (res.b - fb.p);
  auto Ja = Ja_.leftCols(ea.nv());
  auto Jb = Jb_.leftCols(eb.nv());
  ea.frameJacobian(ba.frame, la, Ja);
  eb.frameJacobian(bb.frame, lb, Jb);
  const Eigen::Vector3d& nrm = res.normal;
  const double dt = p.settings().dt;
  const int oa = p.velocityOffset(ba.entity), ob = p.velocityOffset(bb.entity);
  out.C.block(r, oa, 1, ea.nv()).noalias() -= dt * nrm.transpose() * Ja.bottomRows<3>();
  out.C.block(r, ob, 1, eb.nv()).noalias() += dt * nrm.transpose() * Jb.bottomRows<3>();
  // The witnesses' twists (ω; velocity of the witness point), then ḋ and the drift of d̈ at q̈ = 0:
  // the witnesses' J̇ v and the curvature part (collision/distance_rate.hpp).
  Vector6d ta, tb;
  ta.noalias() = Ja * ea.v();
  tb.noalias() = Jb * eb.v();
  const double ddot = nrm.dot(tb.tail<3>() - ta.tail<3>());
  collision::RigidMotion ma, mb;
  ma.omega = ta.head<3>();
  ma.v = ta.tail<3>();
  ma.at = res.a;
  mb.omega = tb.head<3>();
  mb.v = tb.tail<3>();
  mb.at = res.b;
  const double drift = nrm.dot(eb.frameBiasAcceleration(bb.frame, lb).tail<3>() -
                               ea.frameBiasAcceleration(ba.frame, la).tail<3>()) +
                       collision::distanceCurvature(res, ba.shape.radius, bb.shape.radius, ma, mb, dt);
  row_pair_[ur] = k;
  row_e_[ur] = (res.distance - c.security) / (c.interaction - c.security);
  row_ddot_[ur] = ddot;
  row_rate_[ur] = ddot + 0.5 * dt * drift;
}

double CollisionConstraint::measureMinDistance(const MultiRobotProblem& p, int* pair_index) const noexcept {
  double best = std::numeric_limits<double>::infinity();
  for (int k = 0; k < pairCount(); ++k) {
    const CollisionPair& c = pairs_[static_cast<std::size_t>(k)];
    collision::DistanceResult r;
    collision::distance(placed(p, c.a), placed(p, c.b), &r);
    if (r.distance < best) {
      best = r.distance;
      if (pair_index != nullptr) *pair_index = k;
    }
  }
  return best;
}

}  // namespace mrqp::problem
