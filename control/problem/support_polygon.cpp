#include "problem/support_polygon.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace mrqp::problem {

namespace {
double cross(const Eigen::Vector2d& o, const Eigen::Vector2d& a, const Eigen::Vector2d& b) noexcept {
  return (a.x() - o.x()) * (b.y() - o.y()) - (a.y() - o.y()) * (b.x() - o.x());
}
}  // namespace

bool SupportPolygon::add(const Eigen::Vector3d& p) noexcept {
  if (n_points_ >= kMaxPoints) return false;
  pts_[static_cast<std::size_t>(n_points_++)] = p.head<2>();
  return true;
}

void SupportPolygon::build() noexcept {
  n_edges_ = 0;
  if (n_points_ < 3) return;
  auto* begin = pts_.data();
  auto* end = pts_.data() + n_points_;
  std::sort(begin, end, [](const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
  });
  // Andrew's monotone chain, counter-clockwise, collinear points dropped.
  int k = 0;
  for (int i = 0; i < n_points_; ++i) {
    while (k >= 2 && cross(hull_[static_cast<std::size_t>(k - 2)], hull_[static_cast<std::size_t>(k - 1)],
                           pts_[static_cast<std::size_t>(i)]) <= 1e-12) {
      --k;
    }
    hull_[static_cast<std::size_t>(k++)] = pts_[static_cast<std::size_t>(i)];
  }
  for (int i = n_points_ - 2, lower = k + 1; i >= 0; --i) {
    while (k >= lower && cross(hull_[static_cast<std::size_t>(k - 2)], hull_[static_cast<std::size_t>(k - 1)],
                               pts_[static_cast<std::size_t>(i)]) <= 1e-12) {
      --k;
    }
    hull_[static_cast<std::size_t>(k++)] = pts_[static_cast<std::size_t>(i)];
  }
  const int m = k - 1;  // the last point repeats the first
  if (m < 3) return;
  for (int i = 0; i < m; ++i) {
    const Eigen::Vector2d& p = hull_[static_cast<std::size_t>(i)];
    const Eigen::Vector2d& q = hull_[static_cast<std::size_t>(i + 1)];
    const Eigen::Vector2d e = q - p;
    const Eigen::Vector2d inward = Eigen::Vector2d(-e.y(), e.x()).normalized();  // left of a CCW edge
    a_[static_cast<std::size_t>(i)] = inward;
    b_[static_cast<std::size_t>(i)] = inward.dot(p);
  }
  n_edges_ = m;
}

double SupportPolygon::margin(const Eigen::Vector2d& c) const noexcept {
  if (n_edges_ == 0) return -std::numeric_limits<double>::infinity();
  double m = std::numeric_limits<double>::infinity();
  for (int i = 0; i < n_edges_; ++i) m = std::min(m, distance(i, c));
  return m;
}

}  // namespace mrqp::problem
