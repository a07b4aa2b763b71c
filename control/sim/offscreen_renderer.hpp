// Headless rendering of a MuJoCo model with Mesa through EGL (docs/mujoco.md, "Rendering"):
// EGL_PLATFORM=surfaceless, an OpenGL context made current with EGL_NO_SURFACE, then MuJoCo's
// own renderer into its offscreen buffer (mjr_makeContext, mjr_setBuffer(mjFB_OFFSCREEN),
// mjr_render, mjr_readPixels). Host-side: allocates, throws std::runtime_error; one renderer per
// thread (the context is current on the thread that made it).
#pragma once

#include <mujoco/mujoco.h>

#include "sim/png_image.hpp"

namespace mrqp::sim {

class OffscreenRenderer {
 public:
  /// width × height at most the model's offscreen buffer (visual/global offwidth, offheight).
  OffscreenRenderer(const mjModel* model, int width, int height);
  ~OffscreenRenderer();
  OffscreenRenderer(const OffscreenRenderer&) = delete;
  OffscreenRenderer& operator=(const OffscreenRenderer&) = delete;

  /// A free camera that sees the whole scene at `data`'s state, from `azimuth` and `elevation`
  /// (degrees, MuJoCo's: azimuth 0 looks along +x, elevation < 0 from above).
  mjvCamera sceneCamera(const mjData* data, double azimuth = 150.0, double elevation = -20.0) const;
  /// The image of `data` (its kinematics computed, e.g. by mj_forward) seen by `camera`.
  RgbImage render(mjData* data, const mjvCamera& camera);

  int width() const noexcept { return width_; }
  int height() const noexcept { return height_; }

 private:
  const mjModel* model_;
  int width_, height_;
  void* display_ = nullptr;
  void* context_ = nullptr;
  mjvScene scene_{};
  mjvOption option_{};
  mjrContext mjr_{};
  bool mjr_made_ = false, scene_made_ = false;
};

}  // namespace mrqp::sim
