// Collision avoidance between convex shapes carried by frames of one or two entities: the
// velocity damper of eq. 21 written at the acceleration level as eq. 24. For a pair (A, B) with
// signed distance d, witness points a ∈ A, b ∈ B and unit normal n = (b − a)/‖b − a‖
// (control/collision/distance.hpp), once d < δi (interaction distance), with e = (d − δs)/(δi − δs):
//
//   ḋ = nᵀ(J_b v − J_a v),   d̈ = g q̈ + D,   g = nᵀ(J_b − J_a),
//   D = nᵀ(J̇_b v − J̇_a v) + c   (c: the normal turning and the witnesses sliding, distance_rate.hpp,
//                                 over the step Δt: the witnesses kept on their features)
//
// The loop integrates by semi-implicit Euler (v ← v + Δt q̈, q ← q ⊕ Δt v), so over one step
// d_{k+1} = d + Δt ḋ + Δt² (g q̈ + ½ D) + O(Δt³); the row asks d_{k+1} − d ≥ −Δt ξ e, i.e.
//
//   Δt g q̈ ≥ −ξ e − ḋ − ½ Δt D,
//
// eq. 24's ḋ + Δt d̈ ≥ −ξ e for that integration (read literally, with D counted whole, or with c
// left out as in the paper, the bodies settle up to a few tenths of a millimetre inside δs:
// docs/collision.md). J_a, J_b are the world-aligned linear Jacobians of the witness points (each
// on its own entity's columns; both on the same columns for a self-collision pair). Pairs are
// tested first by their bounding balls (collision/bounding_sphere.hpp); those within δi get an
// exact distance; at most `rows` of them, the nearest to their security distance first, get a row;
// the other rows stay free. Where the nearest features of a pair in the nearer half of its range
// are a face or an edge, the rows left over after every candidate pair has its row go to the
// pair's other witnesses, the corners of
// its contact region (collision/contact_witnesses.hpp), each a damper row of the same form on its
// own witness pair with its own distance: one row on a witness that jumps over the region cannot
// hold it. A pair that enters δi approaching faster than ξ allows gets, until it leaves, the
// damping its entry speed needs, ξ' = max(ξ, −ḋ (δi − δs)/(d − δs) + ξ) over its rows (Tasks'
// CollisionConstr does the same), so that its rows never start infeasible.
//
// Real-time: update() is noexcept and allocation-free; shapes, pairs and Jacobian work space are
// fixed at construction.
#pragma once

#include <array>
#include <cstdint>
#include <limits>
#include <memory>
#include <vector>

#include <Eigen/Core>

#include "collision/contact_witnesses.hpp"
#include "collision/distance.hpp"
#include "collision/shape.hpp"
#include "problem/constraint.hpp"

namespace mrqp::problem {

/// One convex shape on a frame of an entity.
struct CollisionBody {
  int entity = -1;
  int frame = -1;
  collision::Shape shape;
  double bound = 0.0;  ///< bounding radius about the shape frame's origin
};

/// A pair of bodies (indices into the constraint's bodies) and its damper: δi > δs ≥ 0 (m), ξ > 0 (m/s).
struct CollisionPair {
  int a = -1, b = -1;
  double interaction = 0.10, security = 0.02, damping = 0.5;
};

class CollisionConstraint final : public Constraint {
 public:
  /// Pairs get their further witnesses (contact_witnesses.hpp) once (d − δs)/(δi − δs) is below
  /// this: in the nearer half of their damper's range, where the bodies are held.
  static constexpr double kWitnessUrgency = 0.5;

  /// `keep_alive` holds whatever the shapes point to (hull vertices); `rows` ≥ 1 inequality rows
  /// are reserved; `max_nv` is the largest nv of the entities involved (Jacobian work space).
  CollisionConstraint(std::vector<CollisionBody> bodies, std::vector<CollisionPair> pairs, int rows,
                      int max_nv, std::vector<std::shared_ptr<const void>> keep_alive = {});

  const char* kind() const noexcept override { return "collision"; }
  int inequalityRows() const noexcept override { return rows_; }
  const char* check(const MultiRobotProblem& p) const noexcept override;
  void update(const MultiRobotProblem& p, ConstraintRows& rows) noexcept override;

  int bodyCount() const noexcept { return static_cast<int>(bodies_.size()); }
  const CollisionBody& body(int i) const noexcept { return bodies_[static_cast<std::size_t>(i)]; }
  int pairCount() const noexcept { return static_cast<int>(pairs_.size()); }
  const CollisionPair& pair(int k) const noexcept { return pairs_[static_cast<std::size_t>(k)]; }
  /// Distance of pair k at the last update; +inf when its bounding balls were farther than δi.
  double lastDistance(int k) const noexcept { return distance_[static_cast<std::size_t>(k)]; }
  /// Smallest distance of the last update (+inf when every pair was filtered out).
  double minDistance() const noexcept { return min_distance_; }
  /// Pairs given a row at the last update.
  int activeRows() const noexcept { return active_; }
  /// The damping ξ' in use for pair k (set when it last entered δi).
  double dampingInUse(int k) const noexcept { return xi_[static_cast<std::size_t>(k)]; }
  /// The pair that row r (< activeRows()) constrained at the last update.
  int rowPair(int r) const noexcept { return row_pair_[static_cast<std::size_t>(r)]; }
  /// The witness pair that row r (< activeRows()) held at the last update: the parts of the two
  /// shapes (the whole shapes for a pair's first row) and their distance, witnesses and normal.
  const collision::Witness& rowWitness(int r) const noexcept { return row_witness_[static_cast<std::size_t>(r)]; }
  /// Pairs within δi at the last update that did not get a row (more than `rows`).
  int droppedPairs() const noexcept { return dropped_; }
  /// Witnesses beyond a pair's first that did not get a row at the last update (rows all used;
  /// the pairs after the one that filled the rows are not searched and not counted).
  int droppedWitnesses() const noexcept { return dropped_witnesses_; }

  /// The exact smallest distance over every pair at the entities' current state (after their
  /// update()), no filter: an independent measurement for reports. Allocation-free.
  double measureMinDistance(const MultiRobotProblem& p, int* pair_index = nullptr) const noexcept;

 private:
  collision::PlacedShape placed(const MultiRobotProblem& p, int body) const noexcept;
  /// Writes row r's coefficients for its witness (row_witness_[r]) of pair k; keeps e, ḋ and the rate.
  void writeRow(const MultiRobotProblem& p, int r, int k, ConstraintRows& out) noexcept;

  std::vector<CollisionBody> bodies_;
  std::vector<CollisionPair> pairs_;
  int rows_;
  std::vector<std::shared_ptr<const void>> keep_alive_;
  std::vector<collision::PlacedShape> placed_;
  std::vector<double> distance_;
  std::vector<collision::DistanceResult> result_;
  std::vector<int> candidates_;
  std::vector<double> xi_;  ///< damping in use per pair (set on entry)
  std::vector<std::uint8_t> was_active_, now_active_;
  std::vector<int> row_pair_;
  std::vector<collision::Witness> row_witness_;
  std::vector<double> row_e_, row_ddot_, row_rate_;  ///< per row: e, ḋ, ḋ + ½ Δt D
  std::array<collision::Witness, collision::kMaxWitnesses> scratch_{};
  Eigen::MatrixXd Ja_, Jb_;
  double min_distance_ = std::numeric_limits<double>::infinity();
  int active_ = 0, dropped_ = 0, dropped_witnesses_ = 0;
};

}  // namespace mrqp::problem
