// The studio's frame time at 1280 x 800, headless, with the live camera view: idle, and while
// both methods train on a recorded session (training must never slow the window below 30
// frames per second). Each frame is what a display would get: snapshot, draw, render; the
// read-back that only screenshots need is measured apart.

#include <benchmark/benchmark.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <memory>
#include <thread>

#include "app/studio/studio_controller.h"
#include "ui/platform/headless_window.h"
#include "ui/studio/studio_ui.h"

namespace {

namespace fs = std::filesystem;
using recon::studio::StudioController;

void WaitIdle(const StudioController& controller) {
  while (!controller.Idle()) std::this_thread::sleep_for(std::chrono::milliseconds(5));
}

/// A studio on a temporary tabletop session with 2 demonstrations, on the Record screen.
class Studio {
 public:
  Studio() : dir_(fs::temp_directory_path() / ("recon-studio-bench-" + std::to_string(getpid()))) {
    fs::remove_all(dir_);
    recon::studio::StudioOptions options;
    options.session_dir = (dir_ / "session").string();
    options.recent_sessions_file = (dir_ / "recent.json").string();
    options.real_time = false;
    options.train_steps = 100;  // the playback benchmark needs checkpoints, not good ones
    options.rollout_tests = 2;
    controller_ = std::make_unique<StudioController>(options);
    controller_->Push(recon::ui::AssignBeacon{"plate", "plate"});
    controller_->Push(recon::ui::StartRecording{});
    WaitIdle();
    controller_->Push(recon::ui::StartRecording{});
    WaitIdle();
    controller_->Push(recon::ui::OpenStep{recon::teach::Step::kRecord});
    WaitIdle();
    window_ = std::make_unique<recon::ui::HeadlessWindow>(
        recon::ui::UiRenderer::Options{1280, 800, 16.0f});
  }
  ~Studio() {
    window_.reset();
    controller_.reset();
    fs::remove_all(dir_);
  }
  void WaitIdle() { ::WaitIdle(*controller_); }
  void Frame() {
    window_->Frame({}, [&] {
      recon::ui::DrawStudio(controller_->Snapshot(), commands_, textures_);
      for (auto& c : commands_.Drain()) controller_->Push(std::move(c));
    });
    glFinishLike();
  }
  recon::ui::HeadlessWindow& window() { return *window_; }
  StudioController& controller() { return *controller_; }

 private:
  // The frame is done when its pixels exist; llvmpipe renders lazily, so wait for it as a
  // swap would (one pixel read-back forces the frame to finish).
  void glFinishLike() { benchmark::DoNotOptimize(window_->Screenshot().width); }

  fs::path dir_;
  std::unique_ptr<StudioController> controller_;
  std::unique_ptr<recon::ui::HeadlessWindow> window_;
  recon::ui::CommandQueue commands_;
  recon::ui::StudioTextures textures_;
};

Studio& Shared() {
  static Studio studio;
  return studio;
}

void BM_StudioFrame1280x800(benchmark::State& state) {
  Studio& studio = Shared();
  for (int i = 0; i < 10; ++i) studio.Frame();  // first frames build the font atlas and tables
  for (auto _ : state) studio.Frame();
  state.counters["frames_per_second"] =
      benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_StudioFrame1280x800)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(2.0);

void BM_StudioFrameWhileTraining(benchmark::State& state) {
  Studio& studio = Shared();
  studio.controller().Push(recon::ui::OpenStep{recon::teach::Step::kTrain});
  studio.controller().Push(recon::ui::StartTraining{{"baseline", "recon"}, 6001});
  std::this_thread::sleep_for(std::chrono::milliseconds(500));  // training is under way
  for (auto _ : state) studio.Frame();
  state.counters["frames_per_second"] =
      benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
  studio.controller().Push(recon::ui::CancelTraining{});
  studio.WaitIdle();
}
BENCHMARK(BM_StudioFrameWhileTraining)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(2.0);

// Both methods' rollouts of one scene playing back side by side (two 320 x 240 renders per
// step shown, at the control rate), on the Rollouts screen.
void BM_StudioFramePlayingRollouts(benchmark::State& state) {
  Studio& studio = Shared();
  studio.controller().Push(recon::ui::StartTraining{{"baseline", "recon"}, 100});
  studio.WaitIdle();
  studio.controller().Push(recon::ui::RunRollouts{2});
  studio.WaitIdle();
  studio.controller().Push(recon::ui::OpenStep{recon::teach::Step::kRollouts});
  studio.controller().Push(recon::ui::PlayRollouts{true});
  studio.WaitIdle();
  for (int i = 0; i < 10; ++i) studio.Frame();
  int64_t playing_frames = 0;
  for (auto _ : state) {
    studio.Frame();
    if (!studio.controller().Snapshot().rollouts_playing) {
      studio.controller().Push(recon::ui::PlayRollouts{true});  // start over at the end
    } else {
      ++playing_frames;
    }
  }
  state.counters["frames_per_second"] =
      benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
  state.counters["playing_share"] =
      static_cast<double>(playing_frames) / static_cast<double>(state.iterations());
}
BENCHMARK(BM_StudioFramePlayingRollouts)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->MinTime(2.0);

// What a teacher waits for between "Train Baseline and RECON" and "Rollouts done": both methods
// trained with the world's recipe on 4 demonstrations and 40 play samples (the paper's robot
// experiment), then rolled out on the studio's 10 test scenes. Target: at most 90 s on 2 cores.
void BM_StudioTrainToRolloutsFourDemos(benchmark::State& state) {
  const fs::path dir =
      fs::temp_directory_path() / ("recon-studio-train-bench-" + std::to_string(getpid()));
  fs::remove_all(dir);
  recon::studio::StudioOptions options;
  options.session_dir = (dir / "session").string();
  options.recent_sessions_file = (dir / "recent.json").string();
  options.real_time = false;
  StudioController controller(options);
  controller.Push(recon::ui::AssignBeacon{"plate", "plate"});
  for (int i = 0; i < 4; ++i) {
    controller.Push(recon::ui::StartRecording{});
    WaitIdle(controller);
  }
  controller.Push(recon::ui::RecordPlay{40});
  WaitIdle(controller);
  double seconds = 0;
  double train_seconds = 0;
  for (auto _ : state) {
    const auto start = std::chrono::steady_clock::now();
    controller.Push(recon::ui::StartTraining{{"baseline", "recon"}});
    WaitIdle(controller);
    train_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    controller.Push(recon::ui::RunRollouts{options.rollout_tests});
    WaitIdle(controller);
    seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }
  state.counters["train_to_rollouts_s"] = seconds;
  // Where the time goes: both methods' training (side by side), then both rollouts.
  state.counters["train_s"] = train_seconds;
  state.counters["rollouts_s"] = seconds - train_seconds;
  for (const recon::ui::TrainingView& t : controller.Snapshot().training) {
    state.counters[t.method + "_train_s"] = t.seconds;
  }
  const recon::ui::StudioSnapshot snapshot = controller.Snapshot();
  if (!snapshot.errors.empty()) state.SkipWithError(snapshot.errors.front().c_str());
  for (const recon::ui::RolloutView& r : snapshot.rollouts) {
    state.counters[r.method + "_success"] = r.success_rate;
  }
  fs::remove_all(dir);
}
BENCHMARK(BM_StudioTrainToRolloutsFourDemos)
    ->Unit(benchmark::kSecond)
    ->UseRealTime()
    ->Iterations(1)
    ->Repetitions(1);

}  // namespace

BENCHMARK_MAIN();
