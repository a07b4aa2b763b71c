// The motion of a run, as people want to see it first (docs/mujoco.md, "Rendering"): the loop's
// program hands the plant to capture() at the times it chooses (off the real-time path: capture
// copies the state and allocates), and finish() renders the stored states headless and writes
// DIR/motion.png, a strip of evenly spaced key frames, and DIR/motion.mp4 through ffmpeg when the
// host has it. Host-side: allocates, throws std::runtime_error.
#pragma once

#include <string>
#include <vector>

#include "sim/mujoco_plant.hpp"

namespace mrqp::sim {

struct RecorderOptions {
  std::string out_dir = ".";
  int width = 480, height = 360;  ///< of one frame (even numbers, for the video)
  int key_frames = 6;             ///< frames of the PNG strip
  double fps = 30.0;              ///< of the video, and of capturing through due()
  bool video = true;              ///< write motion.mp4 when ffmpeg is found
  double azimuth = 150.0;         ///< camera, degrees (OffscreenRenderer::sceneCamera)
  double elevation = -20.0;
};

/// What finish() wrote.
struct RecorderOutput {
  std::string strip;  ///< DIR/motion.png
  std::string video;  ///< DIR/motion.mp4, empty when none was made
  std::string note;   ///< why there is no video, if so
  int frames = 0;
};

class Recorder {
 public:
  Recorder(const MujocoPlant& plant, RecorderOptions options);

  /// Whether the plant's time has reached the next frame time (one frame every 1/fps s).
  bool due() const noexcept;
  /// Stores the plant's current state (time, qpos).
  void capture();
  std::size_t size() const noexcept { return times_.size(); }

  /// Renders the stored states; throws when nothing was captured.
  RecorderOutput finish();

 private:
  const MujocoPlant& plant_;
  RecorderOptions options_;
  std::vector<double> times_;
  std::vector<std::vector<double>> states_;
  double next_ = 0.0;
};

/// The path of `program` found in PATH, empty when it is not there.
std::string findProgram(const std::string& program);

}  // namespace mrqp::sim
