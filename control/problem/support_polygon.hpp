// The support polygon of an entity: the convex hull of its environment contact points projected
// on the ground plane (x, y), as half-planes aᵀc ≥ b with unit inward normals a. Fixed capacity,
// no allocation: used every cycle by the CoM damper (paper 2, eq. 7).
#pragma once

#include <Eigen/Core>

#include <array>

namespace mrqp::problem {

class SupportPolygon {
 public:
  static constexpr int kMaxPoints = 64;

  void clear() noexcept {
    n_points_ = 0;
    n_edges_ = 0;
  }
  /// Adds a point (world, only x and y are used). Returns false once the capacity is full.
  bool add(const Eigen::Vector3d& p) noexcept;
  /// Computes the hull (Andrew's monotone chain) and its half-planes. Fewer than 3 distinct
  /// non-collinear points give no edges (no polygon).
  void build() noexcept;

  int edges() const noexcept { return n_edges_; }
  /// Unit inward normal and offset of edge i: the polygon is {c : normal(i)ᵀc ≥ offset(i)}.
  const Eigen::Vector2d& normal(int i) const noexcept { return a_[static_cast<std::size_t>(i)]; }
  double offset(int i) const noexcept { return b_[static_cast<std::size_t>(i)]; }
  /// Signed distance of c to edge i (positive inside).
  double distance(int i, const Eigen::Vector2d& c) const noexcept { return normal(i).dot(c) - offset(i); }
  /// Smallest signed distance to the edges (positive inside); −inf without a polygon.
  double margin(const Eigen::Vector2d& c) const noexcept;
  int hullSize() const noexcept { return n_edges_; }
  const Eigen::Vector2d& hullPoint(int i) const noexcept { return hull_[static_cast<std::size_t>(i)]; }

 private:
  std::array<Eigen::Vector2d, kMaxPoints> pts_{};
  std::array<Eigen::Vector2d, kMaxPoints + 1> hull_{};
  std::array<Eigen::Vector2d, kMaxPoints> a_{};
  std::array<double, kMaxPoints> b_{};
  int n_points_ = 0, n_edges_ = 0;
};

}  // namespace mrqp::problem
