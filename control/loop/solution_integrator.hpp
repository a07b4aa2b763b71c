// The model as its own plant (docs/loop.md): every entity of a problem advanced over dt by the
// accelerations q̈ of a problem's last Optimal solve, semi-implicit Euler (v ← v + q̈ dt, then
// q ← q ⊕ v dt, each entity's own integration: SE(3) for a floating base or a free object).
//
// MultiRobotProblem only assembles and solves; advancing a state is the loop layer's. Two uses:
// a program or a test that runs a scene on its own models (`integrateSolution(p, dt)`: the
// controller's problem moves itself, mrqp-scene's and the scene tests' closed loop), and the
// ideal plant, a second problem of the same scene moved by the controller's solution
// (`integrateSolution(world, model, dt)`). Header-only, so that anything that links the problem
// can use it; noexcept and allocation-free.
#pragma once

#include "problem/multi_robot_problem.hpp"

namespace mrqp::loop {

/// Advances every entity of `world` by the accelerations of `model`'s last Optimal solve over dt.
/// `world` and `model` hold the same entities in the same order (they may be the same problem).
inline void integrateSolution(problem::MultiRobotProblem& world, const problem::MultiRobotProblem& model,
                              double dt) noexcept {
  for (int i = 0; i < world.entityCount(); ++i) {
    world.entity(i).integrate(model.acceleration(i), dt);
  }
}

/// The problem as its own plant: advances every entity by its own last solution over dt.
inline void integrateSolution(problem::MultiRobotProblem& problem, double dt) noexcept {
  integrateSolution(problem, problem, dt);
}

}  // namespace mrqp::loop
