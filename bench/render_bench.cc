// Speed of the simulated camera: one frame of a small tabletop-like scene (grey floor, two boxes,
// a directional light, top-down camera) through MujocoRenderer on Mesa's llvmpipe, i.e. scene
// update + render + read-back + row flip. frames_per_second is the figure to compare with the
// 200 frames/s the image-based worlds need at 64x64.
//
//   ninja -C build/release render_bench && build/release/bench/render_bench
//
// BM_RenderMovingBox moves the box (mj_forward, included in the time) between frames, as a
// simulation would. The renderer always turns shadows and reflections off; the offsamples=4
// variants show what a scene that forgets <quality offsamples="0"/> pays.

#include <benchmark/benchmark.h>
#include <mujoco/mujoco.h>

#include <string>

#include "devices/render/mujoco_renderer.h"
#include "engine/worlds/mujoco_model.h"
#include "tests/render/test_scene.h"

namespace recon::render {
namespace {

// The scene of tests/render/test_scene.h, with the multisampling as a parameter.
std::string Scene(int offsamples) {
  std::string xml = testing::kTestScene;
  const std::string setting = "offsamples=\"0\"";
  xml.replace(xml.find(setting), setting.size(),
              "offsamples=\"" + std::to_string(offsamples) + "\"");
  return xml;
}

void SetFramesPerSecond(benchmark::State& state) {
  state.counters["frames_per_second"] =
      benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}

// Args: {image width and height, offsamples}.
void BM_RenderMovingBox(benchmark::State& state) {
  const int size = static_cast<int>(state.range(0));
  worlds::MujocoModel scene =
      worlds::MujocoModel::FromString(Scene(static_cast<int>(state.range(1))), "render bench");
  MujocoRenderer renderer;
  mj_forward(scene.model(), scene.data());
  renderer.Render(scene, "top", size, size);  // makes MuJoCo's GPU context: not timed
  int frame = 0;
  for (auto _ : state) {
    scene.data()->mocap_pos[0] = -0.5 + 0.001 * (frame++ % 1000);
    mj_forward(scene.model(), scene.data());
    RgbImage image = renderer.Render(scene, "top", size, size);
    benchmark::DoNotOptimize(image.rgb.data());
  }
  SetFramesPerSecond(state);
}
BENCHMARK(BM_RenderMovingBox)
    ->ArgNames({"size", "offsamples"})
    ->Args({64, 0})
    ->Args({256, 0})
    ->Args({64, 4})
    ->Args({256, 4})
    ->Unit(benchmark::kMicrosecond)
    // llvmpipe rasterises on its own threads: CPU time of this thread would flatter the rate.
    ->UseRealTime();

// The one-off cost of a renderer's first frame of a model (EGL context + mjr_makeContext).
void BM_FirstFrame(benchmark::State& state) {
  worlds::MujocoModel scene = worlds::MujocoModel::FromString(Scene(0), "render bench");
  mj_forward(scene.model(), scene.data());
  for (auto _ : state) {
    MujocoRenderer renderer;
    RgbImage image = renderer.Render(scene, "top", 64, 64);
    benchmark::DoNotOptimize(image.rgb.data());
  }
}
BENCHMARK(BM_FirstFrame)->Unit(benchmark::kMillisecond)->Iterations(5)->UseRealTime();

}  // namespace
}  // namespace recon::render

BENCHMARK_MAIN();
