// Rendering a run after the fact (see recorder.hpp).
#include "sim/recorder.hpp"

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <stdexcept>

#include "sim/offscreen_renderer.hpp"
#include "sim/png_image.hpp"

namespace mrqp::sim {

std::string findProgram(const std::string& program) {
  const char* path = std::getenv("PATH");
  std::string dirs = path != nullptr ? path : "/usr/bin:/bin";
  std::size_t start = 0;
  while (start <= dirs.size()) {
    const std::size_t end = dirs.find(':', start);
    const std::string dir = dirs.substr(start, end == std::string::npos ? std::string::npos : end - start);
    const std::string candidate = (dir.empty() ? "." : dir) + "/" + program;
    if (::access(candidate.c_str(), X_OK) == 0) {
      return candidate;
    }
    if (end == std::string::npos) {
      break;
    }
    start = end + 1;
  }
  return {};
}

Recorder::Recorder(const MujocoPlant& plant, RecorderOptions options)
    : plant_(plant), options_(std::move(options)) {
  if (options_.width <= 0 || options_.height <= 0 || options_.width % 2 != 0 || options_.height % 2 != 0) {
    throw std::runtime_error("recorder: frame size must be positive even numbers");
  }
  if (options_.key_frames < 1 || !(options_.fps > 0.0)) {
    throw std::runtime_error("recorder: key_frames >= 1 and fps > 0 needed");
  }
  next_ = plant_.time();
}

bool Recorder::due() const noexcept { return plant_.time() + 1e-9 >= next_; }

void Recorder::capture() {
  const mjModel* m = plant_.model();
  const mjData* d = plant_.data();
  times_.push_back(d->time);
  states_.emplace_back(d->qpos, d->qpos + m->nq);
  next_ = d->time + 1.0 / options_.fps;
}

RecorderOutput Recorder::finish() {
  if (states_.empty()) {
    throw std::runtime_error("recorder: no frame was captured");
  }
  const mjModel* m = plant_.model();
  std::unique_ptr<mjData, void (*)(mjData*)> d(mj_makeData(m), mj_deleteData);
  OffscreenRenderer renderer(m, options_.width, options_.height);
  const auto place = [&](std::size_t i) {
    std::copy(states_[i].begin(), states_[i].end(), d->qpos);
    d->time = times_[i];
    mj_forward(m, d.get());
  };
  // One camera for the whole run: framed on the first state.
  place(0);
  const mjvCamera camera = renderer.sceneCamera(d.get(), options_.azimuth, options_.elevation);

  RecorderOutput out;
  out.frames = static_cast<int>(states_.size());
  const std::size_t n = states_.size();
  const std::size_t keys = std::min<std::size_t>(static_cast<std::size_t>(options_.key_frames), n);
  std::vector<RgbImage> strip;
  for (std::size_t k = 0; k < keys; ++k) {
    const std::size_t i = keys == 1 ? n - 1 : k * (n - 1) / (keys - 1);
    place(i);
    strip.push_back(renderer.render(d.get(), camera));
  }
  out.strip = options_.out_dir + "/motion.png";
  writePng(out.strip, horizontalStrip(strip));

  if (!options_.video) {
    out.note = "video not asked for";
    return out;
  }
  const std::string ffmpeg = findProgram("ffmpeg");
  if (ffmpeg.empty()) {
    out.note = "no ffmpeg in PATH: no motion.mp4";
    return out;
  }
  const std::string video = options_.out_dir + "/motion.mp4";
  char fps[32];
  std::snprintf(fps, sizeof fps, "%.6g", options_.fps);
  const std::string command = "'" + ffmpeg + "' -y -loglevel error -f rawvideo -pix_fmt rgb24 -s " +
                              std::to_string(options_.width) + "x" + std::to_string(options_.height) +
                              " -r " + fps + " -i - -pix_fmt yuv420p -c:v libx264 '" + video + "'";
  FILE* pipe = ::popen(command.c_str(), "w");
  if (pipe == nullptr) {
    out.note = "cannot start ffmpeg: no motion.mp4";
    return out;
  }
  for (std::size_t i = 0; i < n; ++i) {
    place(i);
    const RgbImage frame = renderer.render(d.get(), camera);
    if (std::fwrite(frame.pixels.data(), 1, frame.pixels.size(), pipe) != frame.pixels.size()) {
      break;
    }
  }
  if (::pclose(pipe) != 0) {
    out.note = "ffmpeg failed: no motion.mp4";
    std::remove(video.c_str());
    return out;
  }
  out.video = video;
  return out;
}

}  // namespace mrqp::sim
