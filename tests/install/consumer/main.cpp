// A user's program on an installed mrqp: its own generated Panda model, registered under the name
// the scene file uses, and a few control cycles of that scene (update, solve, integrate).
// Usage: consumer SCENE.yaml
#include <cmath>
#include <cstdio>
#include <exception>
#include <memory>
#include <string>

#include "loop/solution_integrator.hpp"
#include "model/model_traits.hpp"
#include "problem/model_entity.hpp"
#include "scene/scene_builder.hpp"
#include "user_panda.hpp"

MRQP_MODEL_TRAITS(user_panda);

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: consumer SCENE.yaml\n");
    return 2;
  }
  static user_panda::Data d;
  user_panda::ConfigVector q;
  user_panda::neutral(q);
  user_panda::MassMatrix M;
  user_panda::crba(d, q, M);
  std::printf("panda nq %d nv %d M00 %.6f mass %.4f\n", user_panda::nq, user_panda::nv, M(0, 0),
              user_panda::totalMass());

  mrqp::scene::ModelRegistry models;
  models.add("panda", [](const std::string& name) -> std::unique_ptr<mrqp::problem::Entity> {
    return std::make_unique<mrqp::problem::ModelEntity<user_panda_model>>(name);
  });
  try {
    mrqp::scene::Scene scene = mrqp::scene::loadScene(argv[1], models);
    auto& p = *scene.problem;
    const int cycles = 20;
    for (int k = 0; k < cycles; ++k) {
      p.update();
      if (p.solve() != mrqp::qp::QpStatus::Optimal) {
        std::fprintf(stderr, "consumer: the QP failed at cycle %d\n", k);
        return 1;
      }
      mrqp::loop::integrateSolution(p, scene.settings.dt);
    }
    std::printf("scene %s: %d cycles solved\n", argv[1], cycles);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "consumer: %s\n", e.what());
    return 1;
  }
  return 0;
}
