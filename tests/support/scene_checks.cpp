#include "scene_checks.hpp"

#include <algorithm>

namespace mrqp::testing {

double eomResidual(const problem::MultiRobotProblem& p) {
  double worst = 0.0;
  for (int i = 0; i < p.entityCount(); ++i) {
    const problem::Entity& e = p.entity(i);
    Eigen::VectorXd r = e.massMatrix() * p.acceleration(i) + e.bias() - p.torque(i);
    Eigen::MatrixXd J(6, e.nv());
    for (int c = 0; c < p.contactCapacity(); ++c) {
      if (!p.contactActive(c)) continue;
      const problem::ContactDesc& d = p.contact(c);
      const Eigen::Vector3d at = p.contactPoint(c);
      const problem::Vector6d w = p.contactWrench(c);
      double sign = 0.0;
      int frame = -1;
      if (d.entity == i) {
        sign = 1.0;
        frame = d.frame;
      } else if (d.other_entity == i) {
        sign = -1.0;  // the reaction
        frame = d.other_frame;
      } else {
        continue;
      }
      const problem::Pose P = e.framePose(frame);
      e.frameJacobian(frame, P.R.transpose() * (at - P.p), J);
      r -= sign * J.transpose() * w;
    }
    worst = std::max(worst, r.lpNorm<Eigen::Infinity>() / std::max(1.0, e.bias().lpNorm<Eigen::Infinity>()));
  }
  return worst;
}

double coneViolation(const problem::MultiRobotProblem& p) {
  double worst = 0.0;
  for (int c = 0; c < p.contactCapacity(); ++c) {
    if (!p.contactActive(c)) continue;
    const problem::ContactDesc& d = p.contact(c);
    const problem::Pose P = p.entity(d.entity).framePose(d.frame);
    const Eigen::Vector3d n = P.R * d.normal.normalized();
    const auto lambda = p.lambda(c);
    for (int i = 0; i < d.npoints; ++i) {
      Eigen::Vector3d f = Eigen::Vector3d::Zero();
      for (int k = 0; k < d.generators; ++k) {
        f += lambda(i * d.generators + k) *
             (P.R * problem::coneGenerator(d.normal.normalized(), d.friction, k, d.generators));
      }
      const double fn = f.dot(n);
      const double ft = (f - fn * n).norm();
      worst = std::max({worst, -fn, ft - d.friction * fn});
    }
  }
  return worst;
}

}  // namespace mrqp::testing
