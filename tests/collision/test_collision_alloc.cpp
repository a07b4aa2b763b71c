// The collision constraint on the control cycle allocates nothing: the two-arm scene (arms driven
// into each other, so that pairs come within δi and rows are written) for 3,000 cycles of update,
// solve and integration, counted by the replaced global allocator (libccd's malloc included) and
// checked by Eigen's EIGEN_RUNTIME_NO_MALLOC in every library of the cycle.
#include <catch2/catch.hpp>

#include <string>

#include "collision/collision_constraint.hpp"
#include "counting_allocator.hpp"
#include "scene/builtin_models.hpp"
#include "scene/scene_builder.hpp"

using mrqp::qp::QpStatus;

TEST_CASE("collision: two_arms: 3,000 cycles with active collision rows allocate nothing",
          "[collision][realtime]") {
  mrqp::scene::ModelRegistry models;
  mrqp::scene::addBuiltinModels(models);
  mrqp::scene::Scene s = mrqp::scene::loadScene(std::string(MRQP_SCENES_DIR) + "/two_arms.yaml", models);
  auto& p = *s.problem;
  const auto& c =
      dynamic_cast<const mrqp::problem::CollisionConstraint&>(p.constraint(s.constraints.at("arms")));
  int failures = 0, active = 0;
  p.update();
  const long n = mrqp::testing::allocationsIn([&] {
    for (int k = 0; k < 3000; ++k) {
      p.update();
      if (p.solve() != QpStatus::Optimal) {
        ++failures;
        continue;
      }
      active += c.activeRows() > 0 ? 1 : 0;
      for (int i = 0; i < p.entityCount(); ++i) p.entity(i).integrate(p.acceleration(i), s.settings.dt);
    }
  });
  CHECK(n == 0);
  CHECK(failures == 0);
  CHECK(active > 500);  // the rows were written, not only the filter run
}
