// Headless MuJoCo rendering through EGL (see offscreen_renderer.hpp).
#include "sim/offscreen_renderer.hpp"

#include <EGL/egl.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <stdexcept>
#include <string>
#include <vector>

namespace mrqp::sim {

namespace {
std::string eglErrorText() {
  char buf[32];
  std::snprintf(buf, sizeof buf, "0x%04x", static_cast<unsigned>(eglGetError()));
  return buf;
}
}  // namespace

OffscreenRenderer::OffscreenRenderer(const mjModel* model, int width, int height)
    : model_(model), width_(width), height_(height) {
  if (width <= 0 || height <= 0 || width > model->vis.global.offwidth ||
      height > model->vis.global.offheight) {
    throw std::runtime_error("renderer: image size " + std::to_string(width) + "x" + std::to_string(height) +
                             " outside 1.." + std::to_string(model->vis.global.offwidth) + "x" +
                             std::to_string(model->vis.global.offheight));
  }
  // Mesa's surfaceless platform: no X, no GPU device needed (llvmpipe).
  ::setenv("EGL_PLATFORM", "surfaceless", 0);
  EGLDisplay display = eglGetDisplay(EGL_DEFAULT_DISPLAY);
  if (display == EGL_NO_DISPLAY || eglInitialize(display, nullptr, nullptr) != EGL_TRUE) {
    throw std::runtime_error("renderer: no EGL display (error " + eglErrorText() +
                             "; packages libegl1 libegl-mesa0)");
  }
  display_ = display;
  const EGLint config_attributes[] = {
      EGL_RED_SIZE, 8, EGL_GREEN_SIZE, 8, EGL_BLUE_SIZE, 8, EGL_ALPHA_SIZE, 8, EGL_DEPTH_SIZE, 24,
      EGL_STENCIL_SIZE, 8, EGL_COLOR_BUFFER_TYPE, EGL_RGB_BUFFER,
      // the default (a window) does not exist without a display
      EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE};
  EGLConfig config = nullptr;
  EGLint count = 0;
  if (eglChooseConfig(display, config_attributes, &config, 1, &count) != EGL_TRUE || count < 1) {
    eglTerminate(display);
    throw std::runtime_error("renderer: no EGL configuration for OpenGL (error " + eglErrorText() + ")");
  }
  if (eglBindAPI(EGL_OPENGL_API) != EGL_TRUE) {
    eglTerminate(display);
    throw std::runtime_error("renderer: EGL has no desktop OpenGL (error " + eglErrorText() + ")");
  }
  EGLContext context = eglCreateContext(display, config, EGL_NO_CONTEXT, nullptr);
  if (context == EGL_NO_CONTEXT ||
      eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, context) != EGL_TRUE) {
    eglTerminate(display);
    throw std::runtime_error(
        "renderer: cannot make an OpenGL context current without a surface "
        "(error " +
        eglErrorText() + ")");
  }
  context_ = context;
  mjv_defaultOption(&option_);
  mjv_defaultScene(&scene_);
  mjv_makeScene(model_, &scene_, 4000);
  scene_made_ = true;
  mjr_defaultContext(&mjr_);
  mjr_makeContext(model_, &mjr_, mjFONTSCALE_100);
  mjr_made_ = true;
  mjr_setBuffer(mjFB_OFFSCREEN, &mjr_);
  if (mjr_.currentBuffer != mjFB_OFFSCREEN) {
    throw std::runtime_error("renderer: MuJoCo's offscreen buffer is not available");
  }
}

OffscreenRenderer::~OffscreenRenderer() {
  if (mjr_made_) {
    mjr_freeContext(&mjr_);
  }
  if (scene_made_) {
    mjv_freeScene(&scene_);
  }
  if (display_ != nullptr) {
    eglMakeCurrent(static_cast<EGLDisplay>(display_), EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    if (context_ != nullptr) {
      eglDestroyContext(static_cast<EGLDisplay>(display_), static_cast<EGLContext>(context_));
    }
    eglTerminate(static_cast<EGLDisplay>(display_));
  }
}

mjvCamera OffscreenRenderer::sceneCamera(const mjData* data, double azimuth, double elevation) const {
  mjvCamera cam;
  mjv_defaultFreeCamera(model_, &cam);
  // Look at the bounding box of the bodies (the ground excluded).
  double lo[3] = {1e9, 1e9, 1e9}, hi[3] = {-1e9, -1e9, -1e9};
  for (int b = 1; b < model_->nbody; ++b) {
    for (int i = 0; i < 3; ++i) {
      lo[i] = std::min(lo[i], data->xpos[3 * b + i]);
      hi[i] = std::max(hi[i], data->xpos[3 * b + i]);
    }
  }
  double extent = 0.5;
  if (model_->nbody > 1) {
    for (int i = 0; i < 3; ++i) {
      cam.lookat[i] = 0.5 * (lo[i] + hi[i]);
      extent = std::max(extent, hi[i] - lo[i]);
    }
  }
  cam.distance = 1.2 * extent + 0.6;
  cam.azimuth = azimuth;
  cam.elevation = elevation;
  return cam;
}

RgbImage OffscreenRenderer::render(mjData* data, const mjvCamera& camera) {
  mjvCamera cam = camera;
  mjv_updateScene(model_, data, &option_, nullptr, &cam, mjCAT_ALL, &scene_);
  const mjrRect viewport{0, 0, width_, height_};
  mjr_render(viewport, &scene_, &mjr_);
  RgbImage flipped(width_, height_);
  mjr_readPixels(flipped.pixels.data(), nullptr, viewport, &mjr_);
  // OpenGL's rows run from the bottom.
  RgbImage out(width_, height_);
  for (int y = 0; y < height_; ++y) {
    std::copy(flipped.row(height_ - 1 - y), flipped.row(height_ - 1 - y) + 3 * width_, out.row(y));
  }
  return out;
}

}  // namespace mrqp::sim
