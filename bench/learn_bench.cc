// Speed of the learner: one training step of the authors' Dynamic 2D setup (3x32x32 image, x 2,
// b 2, u 2, batch 20) and policy inference. Time per iteration is one step (ms);
// items_per_second is steps (or observations) per second.
//
//   ninja -C build/release learn_bench && build/release/bench/learn_bench
//
// BM_TrainStepTorchBackend is BM_TrainStepDynamic2DExact trained through LibTorch autograd.
// BM_TrainStepSpatialSoftmax* add NetworkConfig::spatial_softmax to it (either backend).
// The *_Kernels/<name> variants run the same step on each kernel table the CPU supports; the
// threads:2 variant runs two trainers at once (one per core, as experiment sweeps do).
// The images are synthetic but shaped like the world's (background uniform integers in
// [225, 255], coloured 2x2 blocks), so the benchmark does not depend on engine/worlds.

#include <benchmark/benchmark.h>

#include <cmath>
#include <string>

#include "engine/core/malloc_tuning.h"
#include "engine/core/rng.h"
#include "engine/learn/kernels.h"
#include "engine/learn/learner.h"
#include "engine/learn/trainer_impl.h"

namespace recon::learn {
namespace {

constexpr int kSize = 32;

void DrawBlock(std::vector<float>& image, double sx, double sy, float r, float g, float b) {
  const auto index = [](double s) {
    return static_cast<int>(std::nearbyint(kSize * (s + 12.0) / 24.0));
  };
  const int ix = index(sx), iy = index(sy);
  for (int i = ix - 1; i <= ix; ++i) {
    for (int j = iy - 1; j <= iy; ++j) {
      if (i < 0 || j < 0 || i >= kSize || j >= kSize) continue;
      const float rgb[3] = {r, g, b};
      for (int c = 0; c < 3; ++c) image[(c * kSize + i) * kSize + j] = rgb[c];
    }
  }
}

// Ten 10-step demonstrations (plus three play samples each) of a Dynamic-2D-like scene.
Dataset MakeDynamic2DLikeData(uint64_t seed) {
  Rng rng(seed);
  Dataset data;
  data.spec = DataSpec{2, {3, kSize, kSize}, 2, 2};
  for (int scenario = 0; scenario < 10; ++scenario) {
    std::vector<float> background(3 * kSize * kSize);
    for (float& v : background) v = static_cast<float>(225 + rng.UniformInt(31));
    const double t0 = rng.Uniform(-M_PI, M_PI);
    double rx = 0, ry = 0;
    Episode episode;
    for (int step = 0; step < 10; ++step) {
      std::vector<float> image = background;
      DrawBlock(image, rx, ry, 255, 0, 255);
      double red_x = 0, red_y = 0;
      for (int o = 0; o < 4; ++o) {
        const double angle = t0 + o * M_PI / 2 + step * M_PI / 24;
        const double ox = 10 * std::cos(angle), oy = 10 * std::sin(angle);
        const float c = o == 0 ? 10.0f : (o == 2 ? 0.0f : 5.0f);
        DrawBlock(image, ox, oy, c / 10 * 255, (1 - c / 10) * 255, 0);
        if (o == 0) red_x = ox, red_y = oy;
      }
      const double dx = rx - red_x, dy = ry - red_y, norm = std::hypot(dx, dy);
      Sample s;
      s.x = {static_cast<float>(rx), static_cast<float>(ry)};
      s.y = image;
      s.b = {static_cast<float>(red_x), static_cast<float>(red_y)};
      s.u = {static_cast<float>(dx / norm), static_cast<float>(dy / norm)};
      episode.samples.push_back(s);
      if (step < 3) data.play.push_back(PlaySample{s.x, s.y, s.b});
      rx += dx / norm;
      ry += dy / norm;
    }
    data.demos.push_back(episode);
  }
  return data;
}

const Dataset& BenchData() {
  static const Dataset data = MakeDynamic2DLikeData(7);
  return data;
}

Dataset WithoutPlay() {
  Dataset data = BenchData();
  data.play.clear();
  return data;
}

void RunSteps(benchmark::State& state, const Dataset& data, TrainConfig train,
              const NetworkConfig& network = NetworkConfig{}) {
  train.restart_rule = false;
  TrainerImpl trainer(data, network, train);
  for (int i = 0; i < 20; ++i) trainer.Step();  // warm caches and the allocator
  for (auto _ : state) trainer.Step();
  state.SetItemsProcessed(state.iterations());
}

TrainConfig Authors(Method method) {
  TrainConfig train = AuthorsRecipe();
  train.method = method;
  train.steps = 1 << 30;
  return train;
}

void BM_TrainStepDynamic2DExact(benchmark::State& state) {
  RunSteps(state, WithoutPlay(), Authors(Method::kRecon));
}

// The same step with Backend::kTorch: LibTorch operators and autograd instead of our kernels
// (the straight LibTorch port); batch, noise and Adam update are the same.
void BM_TrainStepTorchBackend(benchmark::State& state) {
  TrainConfig train = Authors(Method::kRecon);
  train.backend = Backend::kTorch;
  RunSteps(state, WithoutPlay(), train);
}

void BM_TrainStepDynamic2DExactPlay(benchmark::State& state) {
  RunSteps(state, BenchData(), Authors(Method::kRecon));
}

void BM_TrainStepTwoTrainersAtOnce(benchmark::State& state) {
  RunSteps(state, WithoutPlay(), Authors(Method::kRecon));
}

void BM_TrainStepBaseline(benchmark::State& state) {
  RunSteps(state, WithoutPlay(), Authors(Method::kBaseline));
}

void BM_TrainStepNll(benchmark::State& state) {
  TrainConfig train = Authors(Method::kRecon);
  train.loss = LossKind::kNll;
  RunSteps(state, WithoutPlay(), train);
}

// The authors' CNN with the spatial-softmax keypoint layer after its last block: 16 x 5 x 5
// planes become 32 keypoints, so the first linear layer shrinks from 400 inputs to 32.
NetworkConfig WithKeypoints() {
  NetworkConfig network;
  network.spatial_softmax = true;
  return network;
}

void BM_TrainStepSpatialSoftmax(benchmark::State& state) {
  RunSteps(state, WithoutPlay(), Authors(Method::kRecon), WithKeypoints());
}

void BM_TrainStepSpatialSoftmaxTorchBackend(benchmark::State& state) {
  TrainConfig train = Authors(Method::kRecon);
  train.backend = Backend::kTorch;
  RunSteps(state, WithoutPlay(), train, WithKeypoints());
}

// The tabletop recipe's step (engine/experiments/recipe.cc): RECON (Play) on 3 x 64 x 64 camera
// images (pixels scaled to 0-1), x 7, b 2, u 7 predicted in chunks of 10 by a (128, 128) policy,
// Gaussian NLL, batch 20 of demonstrations and 20 of play. bench/pytorch_reference.py times the
// same network and step in plain PyTorch.
Dataset MakeTabletopLikeData(uint64_t seed) {
  Rng rng(seed);
  Dataset data;
  data.spec = DataSpec{7, {3, 64, 64}, 2, 7};
  for (int demo = 0; demo < 4; ++demo) {
    Episode episode;
    for (int t = 0; t < 120; ++t) {
      Sample s;
      s.y.resize(3 * 64 * 64);
      for (float& v : s.y) v = static_cast<float>(rng.UniformInt(256));
      for (int k = 0; k < 7; ++k) {
        s.x.push_back(static_cast<float>(rng.Normal()));
        s.u.push_back(static_cast<float>(rng.Normal()));
      }
      s.b = {static_cast<float>(rng.Normal()), static_cast<float>(rng.Normal())};
      if (t % 12 == 0) data.play.push_back(PlaySample{s.x, s.y, s.b});
      episode.samples.push_back(std::move(s));
    }
    data.demos.push_back(std::move(episode));
  }
  return data;
}

void BM_TrainStepTabletop(benchmark::State& state) {
  static const Dataset data = MakeTabletopLikeData(11);
  NetworkConfig network;
  network.policy_hidden = {512, 512};  // the tabletop recipe's (engine/experiments/recipe.cc)
  network.image_scale = 1.0f / 255.0f;
  network.action_chunk = 10;
  TrainConfig train;
  train.steps = 1 << 30;
  RunSteps(state, data, train, network);
}

void BM_ActBatch100(benchmark::State& state) {
  const Dataset data = WithoutPlay();
  TrainerImpl trainer(data, NetworkConfig{}, Authors(Method::kRecon));
  for (int i = 0; i < 10; ++i) trainer.Step();
  const Policy policy(trainer.MakePolicy());
  std::vector<std::vector<float>> xs, ys;
  for (int i = 0; i < 100; ++i) {
    const Sample& s = data.demos[i / 10].samples[i % 10];
    xs.push_back(s.x);
    ys.push_back(s.y);
  }
  for (auto _ : state) benchmark::DoNotOptimize(policy.ActBatch(xs, ys));
  state.SetItemsProcessed(state.iterations() * 100);
}

void BM_TrainStepKernels(benchmark::State& state, std::string name) {
  const std::string before = kernels::Kernels().name;
  kernels::UseKernels(name);
  RunSteps(state, WithoutPlay(), Authors(Method::kRecon));
  kernels::UseKernels(before);
}

BENCHMARK(BM_TrainStepDynamic2DExact)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_TrainStepTorchBackend)->Unit(benchmark::kMillisecond);
// Two trainers at once, one per core, as in experiment sweeps: the time is wall-clock per step of
// the pair, items_per_second the total steps per second.
BENCHMARK(BM_TrainStepTwoTrainersAtOnce)->Unit(benchmark::kMillisecond)->Threads(2)->UseRealTime();
BENCHMARK(BM_TrainStepDynamic2DExactPlay)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_TrainStepBaseline)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_TrainStepNll)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_TrainStepSpatialSoftmax)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_TrainStepSpatialSoftmaxTorchBackend)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_TrainStepTabletop)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ActBatch100)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace recon::learn

int main(int argc, char** argv) {
  recon::TuneMallocForTraining();
  recon::learn::SetThreads(1);
  for (const std::string& name : recon::learn::kernels::AvailableKernels()) {
    benchmark::RegisterBenchmark(("BM_TrainStepDynamic2DExact_Kernels/" + name).c_str(),
                                 recon::learn::BM_TrainStepKernels, name)
        ->Unit(benchmark::kMillisecond);
  }
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
