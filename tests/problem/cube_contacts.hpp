// Cubes and their square contacts for the problem tests: a uniform cube of edge 0.1 m as a
// RigidObject, the four corner points of a square contact face, and the capacities of a small
// problem of a few such bodies in contact (no constraints).
#pragma once

#include <Eigen/Core>

#include <memory>

#include "problem/contact.hpp"
#include "problem/multi_robot_problem.hpp"
#include "problem/rigid_object.hpp"

namespace problemtest {

// A cube of mass m and edge 0.1 m (inertia m 0.1² / 6 about each axis), its origin at p, its
// centre of mass at `com` in its own frame.
inline std::unique_ptr<mrqp::problem::Entity> cube(const char* name, double m, const Eigen::Vector3d& p,
                                                   const Eigen::Vector3d& com = Eigen::Vector3d::Zero()) {
  auto e = std::make_unique<mrqp::problem::RigidObject>(name, m, com,
                                                        Eigen::Matrix3d::Identity() * (m * 0.1 * 0.1 / 6.0));
  e->q().head<3>() = p;
  return e;
}

// A contact of `entity`'s frame 0 at the four corners (±half, ±half, z) of a square face; the
// other fields (normal, friction, generators, other entity) as ContactDesc sets them.
inline mrqp::problem::ContactDesc squareContact(int entity, double half, double z) {
  mrqp::problem::ContactDesc c;
  c.entity = entity;
  c.frame = 0;
  c.npoints = 4;
  c.points[0] = {-half, -half, z};
  c.points[1] = {half, -half, z};
  c.points[2] = {half, half, z};
  c.points[3] = {-half, half, z};
  return c;
}

// Room for 4 contacts of 64 generators in all and 4 tasks, no constraint.
inline mrqp::problem::ProblemSettings contactProblemSettings() {
  mrqp::problem::ProblemSettings s;
  s.max_contacts = 4;
  s.max_contact_generators = 64;
  s.max_tasks = 4;
  s.max_constraints = 0;
  s.max_constraint_rows = 0;
  s.max_constraint_equalities = 0;
  return s;
}

}  // namespace problemtest
