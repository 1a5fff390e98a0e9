// Speed of the session store on the tabletop cell's shapes (x 7, y 3x64x64 uint8, b 2, u 7), on
// real files under the system temp folder:
//
//   ninja -C build/release store_bench && build/release/bench/store_bench
//
// BM_CommitEpisode150x64x64: one 150-sample demonstration committed into a session that starts
//   empty (write to a temporary file, fsync, rename, index rebuild); the issue asks for under
//   20 ms. image_MB_per_s is the rate of image data as stored (uint8, 1.84 MB per episode).
// BM_CommitEpisode150x64x64Into100: the same commit into a session already holding 100
//   episodes, to show what the index rebuild costs as a session grows.
// BM_WriteEpisodeFile150x64x64: the episode file alone (no fsync, rename or index): the part of a
//   commit that is encoding and HDF5, so the rest is durability.
// BM_OpenSession100: opening a session of 100 such episodes read-write (lock, scan, every
//   episode's attributes and shapes, index rebuild); the issue asks for under 1 s.
// BM_OpenSession100ReadOnly: the same without the lock and the index rebuild.
// BM_LoadDataset100: loading all 15,000 samples into a training Dataset; the issue asks for
//   under 2 s. Every load goes into memory the process has not touched yet, as a training run's
//   does (the page faults are a large part of it). peak_rss_MB is the process's resident peak
//   while loading, dataset_MB what the Dataset's vectors hold (images become floats: 4x their
//   size on disk); MB are 10^6 bytes.
//
// The 100-episode session is written once per process (about 185 MB) and reused by every
// repetition; it is deleted at exit. The files are fresh, so reads come from the page cache:
// these are warm-cache numbers, as when a teacher trains right after recording.

#include <benchmark/benchmark.h>
#include <malloc.h>
#include <unistd.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>

#include "engine/core/dataset.h"
#include "engine/core/rng.h"
#include "engine/store/episode_file.h"
#include "engine/store/manifest.h"
#include "engine/store/session.h"

namespace recon::store {
namespace {

namespace fs = std::filesystem;

constexpr int kEpisodeSamples = 150;
constexpr int kImageSide = 64;
constexpr int kImageValues = 3 * kImageSide * kImageSide;
constexpr int kSessionEpisodes = 100;
constexpr uint64_t kSeed = 20261122;

/// A fresh folder under the system temp folder, removed with everything in it when it goes.
class TempFolder {
 public:
  explicit TempFolder(const std::string& name)
      : path_(fs::temp_directory_path() /
              ("recon-store-bench-" + name + "-" + std::to_string(getpid()))) {
    fs::remove_all(path_);
    fs::create_directories(path_);
  }
  ~TempFolder() {
    std::error_code ignored;
    fs::remove_all(path_, ignored);
  }
  TempFolder(const TempFolder&) = delete;
  TempFolder& operator=(const TempFolder&) = delete;

  std::string Path(const std::string& relative = "") const {
    return relative.empty() ? path_.string() : (path_ / relative).string();
  }

 private:
  fs::path path_;
};

/// The tabletop cell's session shapes: the arm's 7 joints, the 64 x 64 top camera stored as
/// uint8, the plate's beacon.
SessionManifest TabletopManifest() {
  SessionManifest m;
  m.created_at = "2026-11-22T00:00:00Z";
  m.created_by = "store_bench";
  m.world = "tabletop";
  m.cell = "simulated";
  m.placement = "plate";
  m.image_size = kImageSide;
  m.step_seconds = 0.1;
  m.devices = {{"camera", "simulated", "64x64"}};
  m.beacons = {{"plate", "the plate", "position", 2, "m"}};
  m.spec.x_dim = 7;
  m.spec.y_shape = {3, kImageSide, kImageSide};
  m.spec.b_dim = 2;
  m.spec.u_dim = 7;
  m.y_encoding = "uint8";
  m.seed = kSeed;
  return m;
}

/// A demonstration whose values follow from `seed`. Pixels are uniform whole numbers 0..255:
/// the store does not compress, so their statistics do not change its speed.
DemoRecord SyntheticEpisode(uint64_t seed) {
  Rng rng(seed);
  DemoRecord record;
  record.meta.seed = seed;
  record.meta.source = "store_bench";
  record.meta.recorded_at = "2026-11-22T00:00:00Z";
  record.meta.teaching_seconds = 0.1 * kEpisodeSamples;
  record.meta.succeeded = true;
  const auto vector = [&rng](int n) {
    std::vector<float> v(n);
    for (float& value : v) value = static_cast<float>(rng.Uniform(-1, 1));
    return v;
  };
  for (int i = 0; i < kEpisodeSamples; ++i) {
    Sample s;
    s.x = vector(7);
    s.y.resize(kImageValues);
    for (float& pixel : s.y) pixel = static_cast<float>(rng.UniformInt(256));
    s.b = vector(2);
    s.u = vector(7);
    record.episode.samples.push_back(std::move(s));
    record.rewards.push_back(i + 1 == kEpisodeSamples ? 1.0 : 0.0);
  }
  return record;
}

/// Bytes of image data one episode stores (uint8).
constexpr double kEpisodeImageBytes = static_cast<double>(kEpisodeSamples) * kImageValues;

/// The 100-episode session, written on first use and deleted at exit. Built through CommitDemo,
/// as a teacher's session is, and closed again so that every benchmark opens it itself.
const TempFolder& Session100() {
  // A static, so that repetitions share it; its destructor deletes the files at exit.
  static const std::unique_ptr<TempFolder> folder = [] {
    auto f = std::make_unique<TempFolder>("session100");
    Session session = Session::Create(f->Path(), TabletopManifest());
    for (int i = 0; i < kSessionEpisodes; ++i) {
      session.CommitDemo(SyntheticEpisode(Rng::Derive(kSeed, static_cast<uint64_t>(i))));
    }
    return f;
  }();
  return *folder;
}

/// A writable session in `target` holding the 100 episodes, without rewriting them: the
/// episode files are hard links (commits only ever rename new files in, never write into a
/// committed one), copied if the folder is on another file system.
Session Clone100(const TempFolder& target) {
  const fs::path source = Session100().Path();
  fs::copy_file(source / "session.json", fs::path(target.Path()) / "session.json");
  fs::create_directories(fs::path(target.Path()) / "play");
  fs::create_directories(fs::path(target.Path()) / "episodes");
  for (const fs::directory_entry& e : fs::directory_iterator(source / "episodes")) {
    const fs::path link = fs::path(target.Path()) / "episodes" / e.path().filename();
    std::error_code error;
    fs::create_hard_link(e.path(), link, error);
    if (error) fs::copy_file(e.path(), link);
  }
  return Session::Open(target.Path(), Session::Access::kReadWrite);
}

/// The process's peak resident memory in MB (10^6 bytes, VmHWM), 0 when unknown.
double PeakResidentMB() {
  std::ifstream status("/proc/self/status");
  std::string key;
  while (status >> key) {
    if (key == "VmHWM:") {
      double kb = 0;
      status >> kb;
      return kb * 1024.0 / 1e6;
    }
    status.ignore(4096, '\n');
  }
  return 0;
}

/// Lowers the peak resident memory to the current one (Linux's clear_refs "5"), so that the
/// peak read afterwards belongs to what ran in between rather than to earlier benchmarks.
void ResetPeakResident() { std::ofstream("/proc/self/clear_refs") << "5"; }

void BM_CommitEpisode150x64x64(benchmark::State& state) {
  const DemoRecord record = SyntheticEpisode(kSeed);
  const TempFolder folder("commit");
  Session session = Session::Create(folder.Path(), TabletopManifest());
  state.counters["episodes_before"] = 0;
  for (auto _ : state) session.CommitDemo(record);
  state.counters["image_MB_per_s"] =
      benchmark::Counter(static_cast<double>(state.iterations()) * kEpisodeImageBytes / 1e6,
                         benchmark::Counter::kIsRate);
}
// A fixed count so that every repetition measures the same session sizes (0..49 episodes).
BENCHMARK(BM_CommitEpisode150x64x64)->Iterations(50)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_CommitEpisode150x64x64Into100(benchmark::State& state) {
  const DemoRecord record = SyntheticEpisode(kSeed);
  const TempFolder folder("commit100");
  Session session = Clone100(folder);
  state.counters["episodes_before"] = static_cast<double>(session.demos().size());
  for (auto _ : state) session.CommitDemo(record);
  state.counters["image_MB_per_s"] =
      benchmark::Counter(static_cast<double>(state.iterations()) * kEpisodeImageBytes / 1e6,
                         benchmark::Counter::kIsRate);
}
BENCHMARK(BM_CommitEpisode150x64x64Into100)
    ->Iterations(50)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

void BM_WriteEpisodeFile150x64x64(benchmark::State& state) {
  const DemoRecord record = SyntheticEpisode(kSeed);
  const SessionManifest manifest = TabletopManifest();
  const TempFolder folder("write");
  const std::string path = folder.Path("episode.h5");
  for (auto _ : state) WriteDemoFile(path, manifest, record);  // truncates: one file on disk
  state.counters["image_MB_per_s"] =
      benchmark::Counter(static_cast<double>(state.iterations()) * kEpisodeImageBytes / 1e6,
                         benchmark::Counter::kIsRate);
}
BENCHMARK(BM_WriteEpisodeFile150x64x64)
    ->Iterations(50)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

void BM_OpenSession100(benchmark::State& state) {
  const std::string dir = Session100().Path();
  for (auto _ : state) {
    Session session = Session::Open(dir, Session::Access::kReadWrite);
    benchmark::DoNotOptimize(session.demos().data());
  }
  state.counters["episodes"] = kSessionEpisodes;
}
BENCHMARK(BM_OpenSession100)->Iterations(20)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_OpenSession100ReadOnly(benchmark::State& state) {
  const std::string dir = Session100().Path();
  for (auto _ : state) {
    Session session = Session::Open(dir, Session::Access::kReadOnly);
    benchmark::DoNotOptimize(session.demos().data());
  }
  state.counters["episodes"] = kSessionEpisodes;
}
BENCHMARK(BM_OpenSession100ReadOnly)->Iterations(20)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_LoadDataset100(benchmark::State& state) {
  const Session session = Session::Open(Session100().Path(), Session::Access::kReadOnly);
  const DatasetOptions options{Split::kAll, /*include_bad=*/false, /*include_play=*/false};
  ResetPeakResident();
  double samples = 0;
  double dataset_bytes = 0;
  for (auto _ : state) {
    Dataset dataset = session.LoadDataset(options);
    benchmark::DoNotOptimize(dataset.demos.data());
    // Freeing 60,000 vectors is not loading: keep it out of the time.
    state.PauseTiming();
    samples += static_cast<double>(dataset.NumDemoSamples());
    dataset_bytes = 0;
    for (const Episode& e : dataset.demos) {
      for (const Sample& s : e.samples) {
        dataset_bytes +=
            static_cast<double>(sizeof(Sample) + sizeof(float) * (s.x.capacity() + s.y.capacity() +
                                                                  s.b.capacity() + s.u.capacity()));
      }
    }
    dataset = {};
    // Hand the freed memory back to the kernel: otherwise the next load reuses pages this
    // process has already touched and takes a fifth of the time (0.3 s instead of 2.5 s on the
    // development VM), which no training run sees: it loads once, into fresh memory.
    malloc_trim(0);
    state.ResumeTiming();
  }
  state.counters["samples_per_second"] = benchmark::Counter(samples, benchmark::Counter::kIsRate);
  state.counters["dataset_MB"] = dataset_bytes / 1e6;
  state.counters["peak_rss_MB"] = PeakResidentMB();
}
// One load per repetition: each takes seconds, and three keep the binary well under a minute.
BENCHMARK(BM_LoadDataset100)->Iterations(1)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
}  // namespace recon::store

BENCHMARK_MAIN();
