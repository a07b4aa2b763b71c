// Headless rendering of a scene (EGL, Mesa): the image is not blank (pixel statistics), the PNG
// written is a PNG of the right size, and the recorder writes a strip of key frames.
#include <catch2/catch.hpp>

#include <sys/stat.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <memory>

#include "sim/offscreen_renderer.hpp"
#include "sim/recorder.hpp"
#include "sim_scenes.hpp"

namespace {

const char* kScene = R"(
entities:
  - name: panda
    model: panda
    pose: {xyz: [0, 0, 0]}
    q: {panda_joint2: -0.3, panda_joint4: -2.2, panda_joint6: 2.0}
  - name: box
    model: rigid_object
    mass: 1.0
    inertia: [0.01, 0.01, 0.01]
    pose: {xyz: [0.5, 0.3, 0.6]}
plant: {geoms: [{entity: box, type: box, size: [0.1, 0.1, 0.1]}]}
)";

/// Width and height from a PNG's IHDR chunk.
std::pair<int, int> pngSize(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  unsigned char h[24] = {};
  f.read(reinterpret_cast<char*>(h), 24);
  const unsigned char sig[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  for (int i = 0; i < 8; ++i) {
    if (h[i] != sig[i]) return {0, 0};
  }
  const auto be = [&](int at) { return (h[at] << 24) | (h[at + 1] << 16) | (h[at + 2] << 8) | h[at + 3]; };
  return {be(16), be(20)};
}

}  // namespace

TEST_CASE("Rendering: a scene renders headless to a non-blank image", "[sim][render]") {
  auto plant = mrqp::sim::testing::makePlant(kScene);
  mrqp::sim::OffscreenRenderer renderer(plant->model(), 320, 240);
  std::unique_ptr<mjData, void (*)(mjData*)> d(mj_makeData(plant->model()), mj_deleteData);
  std::copy(plant->data()->qpos, plant->data()->qpos + plant->model()->nq, d->qpos);
  mj_forward(plant->model(), d.get());
  const mrqp::sim::RgbImage image = renderer.render(d.get(), renderer.sceneCamera(d.get()));
  REQUIRE(image.width == 320);
  REQUIRE(image.height == 240);
  // Statistics of the luminance: a blank (one-colour) image has none of this spread.
  double sum = 0.0, sq = 0.0;
  int distinct_rows = 0;
  const std::size_t n = image.pixels.size() / 3;
  for (std::size_t i = 0; i < n; ++i) {
    const double y =
        0.299 * image.pixels[3 * i] + 0.587 * image.pixels[3 * i + 1] + 0.114 * image.pixels[3 * i + 2];
    sum += y;
    sq += y * y;
  }
  for (int y = 1; y < image.height; ++y) {
    distinct_rows += std::equal(image.row(y), image.row(y) + 3 * image.width, image.row(y - 1)) ? 0 : 1;
  }
  const double mean = sum / static_cast<double>(n);
  const double sd = std::sqrt(sq / static_cast<double>(n) - mean * mean);
  INFO("mean " << mean << ", sd " << sd << ", distinct rows " << distinct_rows);
  CHECK(sd > 10.0);
  CHECK(mean > 10.0);
  CHECK(mean < 245.0);
  CHECK(distinct_rows > image.height / 2);

  const std::string path = "render_test.png";
  mrqp::sim::writePng(path, image);
  CHECK(pngSize(path) == std::make_pair(320, 240));
  std::remove(path.c_str());
}

TEST_CASE("Rendering: the recorder writes a strip of key frames", "[sim][render]") {
  auto plant = mrqp::sim::testing::makePlant(kScene);
  const std::string dir = "recorder_test_out";
  ::mkdir(dir.c_str(), 0755);
  mrqp::sim::RecorderOptions o;
  o.out_dir = dir;
  o.width = 160;
  o.height = 120;
  o.key_frames = 4;
  o.fps = 20.0;
  o.video = false;
  mrqp::sim::Recorder rec(*plant, o);
  for (int i = 0; i < 500; ++i) {
    if (rec.due()) rec.capture();
    plant->step(0.001);
  }
  CHECK(rec.size() == 10);
  const mrqp::sim::RecorderOutput out = rec.finish();
  // Four frames of 160 and three gaps of 4 pixels.
  CHECK(pngSize(out.strip) == std::make_pair(4 * 160 + 3 * 4, 120));
  CHECK(out.video.empty());
  std::remove(out.strip.c_str());
  ::rmdir(dir.c_str());
}
