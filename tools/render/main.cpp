// mrqp-render: the MuJoCo model of a scene file, rendered headless (docs/mujoco.md). Writes
// DIR/scene.png (the initial state); with --duration, simulates that long with every joint held at
// its initial position by its drive and writes DIR/motion.png (key frames) and DIR/motion.mp4
// (when ffmpeg is found); --mjcf writes the model's MJCF text.
#include <sys/stat.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <memory>
#include <string>

#include "scene/builtin_models.hpp"
#include "scene/scene_yaml.hpp"
#include "sim/mujoco_plant.hpp"
#include "sim/offscreen_renderer.hpp"
#include "sim/plant_yaml.hpp"
#include "sim/recorder.hpp"

namespace {

int usage(const char* msg) {
  if (msg != nullptr) std::fprintf(stderr, "mrqp-render: %s\n", msg);
  std::fprintf(stderr,
               "usage: mrqp-render SCENE.yaml --out DIR [--width W] [--height H] [--duration S]\n"
               "                   [--fps F] [--kp KP] [--kd KD] [--azimuth DEG] [--elevation DEG]\n"
               "                   [--mjcf FILE.xml]\n"
               "  Renders the scene's MuJoCo model at its initial state to DIR/scene.png. With\n"
               "  --duration, simulates S seconds with every joint held at its initial position\n"
               "  (drive gains KP, KD; default 2000, 100) and writes DIR/motion.png and, with ffmpeg,\n"
               "  DIR/motion.mp4.\n");
  return 2;
}

bool parseNumber(const char* text, double& out) {
  if (text == nullptr) return false;
  char* end = nullptr;
  errno = 0;
  out = std::strtod(text, &end);
  return end != text && *end == '\0' && errno == 0;
}

}  // namespace

static int unwrappedMain(int argc, char** argv) {
  std::string scene_file, out_dir, mjcf_file;
  double width = 640, height = 480, duration = 0.0, fps = 30.0, kp = 2000.0, kd = 100.0;
  double azimuth = 150.0, elevation = -20.0;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const auto next = [&]() -> const char* { return i + 1 < argc ? argv[++i] : nullptr; };
    const auto number = [&](double& v) {
      const char* t = next();
      if (!parseNumber(t, v)) {
        std::exit(usage((a + ": expected a number").c_str()));
      }
    };
    if (a == "--out") {
      const char* t = next();
      if (t == nullptr) return usage("--out: expected a folder");
      out_dir = t;
    } else if (a == "--mjcf") {
      const char* t = next();
      if (t == nullptr) return usage("--mjcf: expected a file");
      mjcf_file = t;
    } else if (a == "--width") {
      number(width);
    } else if (a == "--height") {
      number(height);
    } else if (a == "--duration") {
      number(duration);
    } else if (a == "--fps") {
      number(fps);
    } else if (a == "--kp") {
      number(kp);
    } else if (a == "--kd") {
      number(kd);
    } else if (a == "--azimuth") {
      number(azimuth);
    } else if (a == "--elevation") {
      number(elevation);
    } else if (a == "-h" || a == "--help") {
      usage(nullptr);
      return 0;
    } else if (!a.empty() && a[0] == '-') {
      return usage(("unknown option " + a).c_str());
    } else if (scene_file.empty()) {
      scene_file = a;
    } else {
      return usage("one scene file only");
    }
  }
  if (scene_file.empty() || out_dir.empty()) return usage("a scene file and --out DIR are needed");
  const int w = static_cast<int>(width), h = static_cast<int>(height);
  if (w < 2 || h < 2 || w % 2 != 0 || h % 2 != 0 || w != width || h != height) {
    return usage("--width and --height: even whole numbers");
  }
  if (duration < 0.0 || !(fps > 0.0)) return usage("--duration >= 0 and --fps > 0");
  try {
    const mrqp::scene::SceneSpec scene = mrqp::scene::loadSceneFile(scene_file);
    const mrqp::sim::PlantSpec plant_spec = mrqp::sim::loadPlantSpec(scene_file);
    mrqp::scene::ModelRegistry registry;
    mrqp::scene::addBuiltinModels(registry);
    mrqp::sim::MujocoPlant plant(scene, plant_spec, &registry);
    if (::mkdir(out_dir.c_str(), 0755) != 0 && errno != EEXIST) {
      throw std::runtime_error(out_dir + ": cannot create: " + std::strerror(errno));
    }
    if (!mjcf_file.empty()) {
      FILE* f = std::fopen(mjcf_file.c_str(), "w");
      if (f == nullptr) throw std::runtime_error(mjcf_file + ": cannot open for writing");
      std::fputs(plant.mjcf().xml.c_str(), f);
      std::fclose(f);
    }
    {
      mrqp::sim::OffscreenRenderer renderer(plant.model(), w, h);
      std::unique_ptr<mjData, void (*)(mjData*)> d(mj_makeData(plant.model()), mj_deleteData);
      std::copy(plant.data()->qpos, plant.data()->qpos + plant.model()->nq, d->qpos);
      mj_forward(plant.model(), d.get());
      mrqp::sim::writePng(out_dir + "/scene.png",
                          renderer.render(d.get(), renderer.sceneCamera(d.get(), azimuth, elevation)));
      std::printf("%s/scene.png\n", out_dir.c_str());
    }
    if (duration > 0.0) {
      for (const mrqp::scene::EntitySpec& e : scene.entities) {
        const int eh = plant.entityHandle(e.name);
        std::unique_ptr<mrqp::problem::Entity> model = registry.make(e.model, e.name);
        if (!model || e.actuation == "none") continue;
        Eigen::VectorXd q(plant.entityNq(eh)), v(plant.entityNv(eh));
        plant.entityState(eh, q, v);
        for (int k = model->jointOffset(); k < model->nv(); ++k) {
          mrqp::loop::ServoCommand c;
          c.enabled = true;
          c.position = q(model->qIndexOfV(k));
          c.kp = kp;
          c.kd = kd;
          plant.setServo(plant.jointHandle(e.name, model->jointName(k - model->jointOffset())), c);
        }
      }
      mrqp::sim::RecorderOptions o;
      o.out_dir = out_dir;
      o.width = w;
      o.height = h;
      o.fps = fps;
      o.azimuth = azimuth;
      o.elevation = elevation;
      mrqp::sim::Recorder recorder(plant, o);
      const double dt = scene.settings.dt;
      while (plant.time() < duration - 1e-9) {
        if (recorder.due()) recorder.capture();
        plant.step(dt);
      }
      recorder.capture();
      const mrqp::sim::RecorderOutput out = recorder.finish();
      std::printf("%s (%d frames)\n", out.strip.c_str(), out.frames);
      if (!out.video.empty()) {
        std::printf("%s\n", out.video.c_str());
      } else {
        std::printf("(%s)\n", out.note.c_str());
      }
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "mrqp-render: %s\n", e.what());
    return 1;
  }
  return 0;
}

// Any exception becomes one error line and exit status 1 (docs/robustness.md).
int main(int argc, char** argv) {
  try {
    return unwrappedMain(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: %s\n", "mrqp-render", e.what());
  } catch (...) {
    std::fprintf(stderr, "%s: unknown error\n", "mrqp-render");
  }
  return 1;
}
