// bench_collision: what collision avoidance costs (docs/BENCHMARKS.md, "Collision avoidance").
//
//   1. collision::distance per shape pair (capsule–capsule, box–box, box–capsule, hull–hull with
//      40-vertex hulls), placements random within reach of each other;
//   2. per pair of the co-manipulation scene: exact distance + the two witness points' Jacobians,
//      J̇v and d̈'s curvature term (what a row of eq. 24 needs), over every enabled pair; and the
//      search for a pair's further witnesses at face and edge contact (collision/contact_witnesses.hpp)
//      on face-to-face box pairs (the case that makes most of them);
//   3. the control cycle (update + solve + integration, the model as its own plant) of
//      tools/scenes/comanipulation.yaml without and with every non-adjacent pair of both robots
//      (JVRC-1 self, Panda self, JVRC-1–Panda) enabled; link pairs whose shapes already overlap or
//      are within δs in the initial posture (JVRC-1's conservative boxes at the hips) are excluded
//      and counted.
//
// Usage: bench_collision [--cycles N] (default 2000). Prints a table; median and p99 in µs.
#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <random>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "collision/collision_constraint.hpp"
#include "collision/contact_witnesses.hpp"
#include "collision/distance.hpp"
#include "collision/distance_rate.hpp"
#include "scene/builtin_models.hpp"
#include "scene/scene_builder.hpp"
#include "scene/scene_yaml.hpp"
#include "scene/yaml_reader.hpp"

using namespace mrqp;
using Clock = std::chrono::steady_clock;

namespace {

double micro(Clock::duration d) { return std::chrono::duration<double, std::micro>(d).count(); }

struct Stats {
  double median, p99;
};

Stats stats(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  if (v.empty()) return {0.0, 0.0};
  return {v[v.size() / 2],
          v[std::min(v.size() - 1, static_cast<std::size_t>(0.99 * static_cast<double>(v.size())))]};
}

Eigen::Matrix3d randomRotation(std::mt19937& rng) {
  std::normal_distribution<double> n(0.0, 1.0);
  return Eigen::Quaterniond(n(rng), n(rng), n(rng), n(rng)).normalized().toRotationMatrix();
}

// ns per distance query between random placements of a and b within 0.3 m.
double timeDistance(const collision::Shape& a, const collision::Shape& b, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-0.15, 0.15);
  constexpr int kPlacements = 2000;
  std::vector<collision::PlacedShape> A, B;
  for (int i = 0; i < kPlacements; ++i) {
    A.push_back(collision::place(a, randomRotation(rng), Eigen::Vector3d(u(rng), u(rng), u(rng))));
    B.push_back(collision::place(b, randomRotation(rng), Eigen::Vector3d(0.3 + u(rng), u(rng), u(rng))));
  }
  collision::DistanceResult r;
  double sink = 0.0;
  const auto t0 = Clock::now();
  for (int rep = 0; rep < 20; ++rep) {
    for (int i = 0; i < kPlacements; ++i) {
      collision::distance(A[static_cast<std::size_t>(i)], B[static_cast<std::size_t>(i)], &r);
      sink += r.distance;
    }
  }
  const double ns = micro(Clock::now() - t0) * 1e3 / (20.0 * kPlacements);
  if (sink == 12345.678) std::printf(" ");
  return ns;
}

const char* kCollisions = R"(
collisions:
  - {name: jvrc_self, entities: [jvrc], interaction: 0.05, security: 0.01, damping: 0.5, max_rows: 32EXCLUDE_JVRC}
  - {name: panda_self, entities: [panda], interaction: 0.05, security: 0.01, damping: 0.5, max_rows: 16EXCLUDE_PANDA}
  - {name: jvrc_panda, entities: [jvrc, panda], interaction: 0.05, security: 0.01, damping: 0.5, max_rows: 16}
)";

std::string withCollisions(const std::string& text, const std::string& jvrc_ex, const std::string& panda_ex) {
  std::string c = kCollisions;
  c.replace(c.find("EXCLUDE_JVRC"), 12, jvrc_ex.empty() ? "" : ", exclude: [" + jvrc_ex + "]");
  c.replace(c.find("EXCLUDE_PANDA"), 13, panda_ex.empty() ? "" : ", exclude: [" + panda_ex + "]");
  return text + c;
}

const problem::CollisionConstraint& collisionOf(const scene::Scene& s, const std::string& name) {
  return dynamic_cast<const problem::CollisionConstraint&>(s.problem->constraint(s.constraints.at(name)));
}

// Link pairs of a self-collision item within δs at the current state, as "[a, b], ..." for exclude.
std::string overlapping(const scene::Scene& s, const std::string& name, int* count) {
  const auto& c = collisionOf(s, name);
  const auto& p = *s.problem;
  std::set<std::pair<std::string, std::string>> out;
  for (int k = 0; k < c.pairCount(); ++k) {
    const auto& pr = c.pair(k);
    const auto& ba = c.body(pr.a);
    const auto& bb = c.body(pr.b);
    const auto fa = p.entity(ba.entity).framePose(ba.frame), fb = p.entity(bb.entity).framePose(bb.frame);
    collision::DistanceResult r;
    collision::distance(collision::place(ba.shape, fa.R, fa.p), collision::place(bb.shape, fb.R, fb.p), &r);
    if (r.distance <= pr.security)
      out.insert({p.entity(ba.entity).frameName(ba.frame), p.entity(bb.entity).frameName(bb.frame)});
  }
  std::string txt;
  for (const auto& [a, b] : out) txt += (txt.empty() ? "[" : ", [") + a + ", " + b + "]";
  *count = static_cast<int>(out.size());
  return txt;
}

struct CycleResult {
  Stats cycle;
  int non_optimal = 0;
  double pairs_evaluated = 0.0, rows = 0.0, dropped = 0.0, dropped_witnesses = 0.0;
};

CycleResult runCycles(scene::Scene& s, int cycles) {
  auto& p = *s.problem;
  std::vector<const problem::CollisionConstraint*> cs;
  for (const auto& [n, id] : s.constraints) {
    if (const auto* c = dynamic_cast<const problem::CollisionConstraint*>(&p.constraint(id))) cs.push_back(c);
  }
  CycleResult out;
  std::vector<double> t;
  t.reserve(static_cast<std::size_t>(cycles));
  for (int k = 0; k < cycles; ++k) {
    const auto t0 = Clock::now();
    p.update();
    const qp::QpStatus st = p.solve();
    t.push_back(micro(Clock::now() - t0));
    for (const auto* c : cs) {
      for (int i = 0; i < c->pairCount(); ++i)
        out.pairs_evaluated += std::isfinite(c->lastDistance(i)) ? 1.0 : 0.0;
      out.rows += c->activeRows();
      out.dropped += c->droppedPairs();
      out.dropped_witnesses += c->droppedWitnesses();
    }
    if (st != qp::QpStatus::Optimal) {
      ++out.non_optimal;
      continue;
    }
    for (int i = 0; i < p.entityCount(); ++i) p.entity(i).integrate(p.acceleration(i), s.settings.dt);
  }
  out.cycle = stats(t);
  out.pairs_evaluated /= cycles;
  out.rows /= cycles;
  out.dropped /= cycles;
  out.dropped_witnesses /= cycles;
  return out;
}

int benchMain(int argc, char** argv) {
  int cycles = 2000;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--cycles") == 0 && i + 1 < argc) {
      cycles = std::atoi(argv[++i]);
    } else {
      std::fprintf(stderr, "usage: bench_collision [--cycles N]\n");
      return 2;
    }
  }
  std::mt19937 rng(1);
  // ---- 1. distance per shape pair ----
  std::uniform_real_distribution<double> u(-0.05, 0.05);
  std::vector<Eigen::Vector3d> h1, h2;
  for (int i = 0; i < 40; ++i) h1.emplace_back(u(rng), u(rng), 2 * u(rng));
  for (int i = 0; i < 40; ++i) h2.emplace_back(u(rng), 2 * u(rng), u(rng));
  const collision::Shape cap = collision::makeCapsule(0.05, 0.2), box = collision::makeBox({0.1, 0.15, 0.2});
  const collision::Shape hull1 = collision::makeHull(h1.data(), 40),
                         hull2 = collision::makeHull(h2.data(), 40);
  std::printf("distance per shape pair (ns):\n");
  std::printf("  capsule-capsule %8.0f\n", timeDistance(cap, cap, rng));
  std::printf("  box-box         %8.0f\n", timeDistance(box, box, rng));
  std::printf("  box-capsule     %8.0f\n", timeDistance(box, cap, rng));
  std::printf("  hull40-hull40   %8.0f\n", timeDistance(hull1, hull2, rng));

  // ---- the co-manipulation scene, with and without collisions ----
  const std::string path = std::string(MRQP_BENCH_SCENES_DIR) + "/comanipulation.yaml";
  const std::string text = scene::readTextFile(path);
  scene::ModelRegistry models;
  scene::addBuiltinModels(models);
  int ex_jvrc = 0, ex_panda = 0;
  std::string jvrc_ex, panda_ex;
  {
    scene::Scene probe =
        scene::buildScene(scene::loadSceneString(withCollisions(text, "", ""), path), models);
    probe.problem->update();
    jvrc_ex = overlapping(probe, "jvrc_self", &ex_jvrc);
    panda_ex = overlapping(probe, "panda_self", &ex_panda);
  }
  scene::Scene with =
      scene::buildScene(scene::loadSceneString(withCollisions(text, jvrc_ex, panda_ex), path), models);
  with.problem->update();
  int pairs = 0;
  for (const char* n : {"jvrc_self", "panda_self", "jvrc_panda"}) pairs += collisionOf(with, n).pairCount();
  std::printf(
      "\ncomanipulation: %d shape pairs enabled (JVRC-1 self %d, Panda self %d, JVRC-1-Panda %d); "
      "excluded as within δs at the start: %d JVRC-1 and %d Panda link pairs\n",
      pairs, collisionOf(with, "jvrc_self").pairCount(), collisionOf(with, "panda_self").pairCount(),
      collisionOf(with, "jvrc_panda").pairCount(), ex_jvrc, ex_panda);

  // ---- 2. per pair: distance + witness Jacobians, J̇v and d̈'s curvature term ----
  {
    const auto& p = *with.problem;
    int maxnv = 0;
    for (int i = 0; i < p.entityCount(); ++i) maxnv = std::max(maxnv, p.entity(i).nv());
    Eigen::MatrixXd Ja(6, maxnv), Jb(6, maxnv);
    double sink = 0.0;
    int n = 0;
    const auto t0 = Clock::now();
    for (int rep = 0; rep < 20; ++rep) {
      for (const char* name : {"jvrc_self", "panda_self", "jvrc_panda"}) {
        const auto& c = collisionOf(with, name);
        for (int k = 0; k < c.pairCount(); ++k) {
          const auto& ba = c.body(c.pair(k).a);
          const auto& bb = c.body(c.pair(k).b);
          const auto& ea = p.entity(ba.entity);
          const auto& eb = p.entity(bb.entity);
          const auto fa = ea.framePose(ba.frame), fb = eb.framePose(bb.frame);
          collision::DistanceResult r;
          collision::distance(collision::place(ba.shape, fa.R, fa.p), collision::place(bb.shape, fb.R, fb.p),
                              &r);
          const Eigen::Vector3d la = fa.R.transpose() * (r.a - fa.p), lb = fb.R.transpose() * (r.b - fb.p);
          auto A = Ja.leftCols(ea.nv());
          auto B = Jb.leftCols(eb.nv());
          ea.frameJacobian(ba.frame, la, A);
          eb.frameJacobian(bb.frame, lb, B);
          sink += r.distance + A(3, 0) + B(3, 0) + ea.frameBiasAcceleration(ba.frame, la)(3) +
                  eb.frameBiasAcceleration(bb.frame, lb)(3);
          // d̈'s curvature term (collision/distance_rate.hpp) from the witnesses' twists.
          const auto ta = A * ea.v(), tb = B * eb.v();
          collision::RigidMotion ma, mb;
          ma.omega = ta.head(3);
          ma.v = ta.tail(3);
          ma.at = r.a;
          mb.omega = tb.head(3);
          mb.v = tb.tail(3);
          mb.at = r.b;
          sink += collision::distanceCurvature(r, ba.shape.radius, bb.shape.radius, ma, mb);
          ++n;
        }
      }
    }
    const double us = micro(Clock::now() - t0) / n;
    if (sink == 12345.678) std::printf(" ");
    std::printf(
        "per pair: distance + 2 witness Jacobians + 2 J̇v + curvature: %.2f µs (mean over %d pairs × 20)\n",
        us, n / 20);
  }

  // ---- 2b. further witnesses: two boxes face to face, random size, offset and turn about the normal ----
  {
    std::uniform_real_distribution<double> w(0.05, 0.3), off(-0.1, 0.1), turn(-3.14159, 3.14159);
    std::vector<collision::Shape> boxes;
    for (int i = 0; i < 64; ++i) boxes.push_back(collision::makeBox({w(rng), w(rng), w(rng)}));
    std::array<collision::Witness, collision::kMaxWitnesses> out;
    double total = 0.0, sink = 0.0;
    int n = 0, witnesses = 0;
    for (int i = 0; i + 1 < static_cast<int>(boxes.size()); i += 2) {
      const collision::Shape& a = boxes[static_cast<std::size_t>(i)];
      const collision::Shape& b = boxes[static_cast<std::size_t>(i + 1)];
      const Eigen::Matrix3d Rb = Eigen::AngleAxisd(turn(rng), Eigen::Vector3d::UnitZ()).toRotationMatrix();
      const Eigen::Vector3d pb(off(rng), off(rng), a.half.z() + b.half.z() + 0.02);
      const collision::PlacedShape A = collision::place(a, Eigen::Matrix3d::Identity(), Eigen::Vector3d::Zero());
      const collision::PlacedShape B = collision::place(b, Rb, pb);
      collision::DistanceResult r;
      collision::distance(A, B, &r);
      const auto t0 = Clock::now();
      int k = 0;
      for (int rep = 0; rep < 200; ++rep) {
        k = collision::contactWitnesses(A, B, r, collision::kWitnessBand, out.data(), collision::kMaxWitnesses);
        sink += out[static_cast<std::size_t>(k - 1)].result.distance;
      }
      total += micro(Clock::now() - t0) / 200.0;
      witnesses += k;
      ++n;
    }
    if (sink == 12345.678) std::printf(" ");
    std::printf("further witnesses of a face-to-face box pair: %.2f µs, %.1f witnesses (mean over %d pairs)\n",
                total / n, static_cast<double>(witnesses) / n, n);
  }

  // ---- 3. the cycle ----
  scene::Scene without = scene::buildScene(scene::loadSceneString(text, path), models);
  const CycleResult a = runCycles(without, cycles);
  const CycleResult b = runCycles(with, cycles);
  std::printf("\ncycle (update + solve), %d cycles      median µs   p99 µs   non-optimal\n", cycles);
  std::printf("  without collisions                  %8.1f %8.1f   %d\n", a.cycle.median, a.cycle.p99,
              a.non_optimal);
  std::printf("  with every non-adjacent pair        %8.1f %8.1f   %d\n", b.cycle.median, b.cycle.p99,
              b.non_optimal);
  std::printf(
      "  per cycle on average: %.1f pairs past the bounding-ball filter, %.2f rows written (witness rows "
      "included), %.2f pairs and %.2f further witnesses dropped\n",
      b.pairs_evaluated, b.rows, b.dropped, b.dropped_witnesses);
  return 0;
}

}  // namespace

static int unwrappedMain(int argc, char** argv) {
  try {
    return benchMain(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_collision: %s\n", e.what());
    return 1;
  }
}

// Any exception becomes one error line and exit status 1 (docs/robustness.md).
int main(int argc, char** argv) {
  try {
    return unwrappedMain(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: %s\n", "bench_collision", e.what());
  } catch (...) {
    std::fprintf(stderr, "%s: unknown error\n", "bench_collision");
  }
  return 1;
}
