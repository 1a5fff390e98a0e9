// Reading a session's episodes back: one at a time, and all of them into a training dataset.

#include <algorithm>
#include <thread>

#include "engine/core/error.h"
#include "engine/core/parallel_for.h"
#include "engine/store/session.h"

namespace recon::store {

DemoRecord Session::ReadDemo(const std::string& name) const {
  const EpisodeEntry& e = Find(name);
  if (!e.problem.empty()) throw UserError(e.problem);
  return ReadDemoFile(e.path, manifest_);
}

PlayRecord Session::ReadPlay(const std::string& name) const {
  const EpisodeEntry& e = Find(name);
  if (!e.problem.empty()) throw UserError(e.problem);
  return ReadPlayFile(e.path, manifest_);
}

namespace {

bool InDataset(const EpisodeEntry& e, const DatasetOptions& options) {
  if (e.flags.bad && !options.include_bad) return false;
  if (options.split == Split::kTrain && e.flags.split != "train") return false;
  if (options.split == Split::kValid && e.flags.split != "valid") return false;
  return true;
}

}  // namespace

std::vector<std::string> Session::DatasetEpisodeNames(const DatasetOptions& options) const {
  std::vector<std::string> names;
  for (const EpisodeEntry& e : demos_) {
    if (InDataset(e, options)) names.push_back(e.name);
  }
  if (options.include_play) {
    for (const EpisodeEntry& e : play_) names.push_back(e.name);
  }
  return names;
}

Dataset Session::LoadDataset(const DatasetOptions& options) const {
  Dataset dataset;
  dataset.spec = manifest_.spec;
  std::vector<const EpisodeEntry*> demos;
  for (const EpisodeEntry& e : demos_) {
    if (!InDataset(e, options)) continue;
    if (!e.problem.empty()) {
      throw UserError(e.problem + " (delete the episode with `recon session delete-episode " +
                      dir_ + " " + e.name + "`, or mark it bad, to train on the others)");
    }
    demos.push_back(&e);
  }
  std::vector<const EpisodeEntry*> chunks;
  if (options.include_play) {
    for (const EpisodeEntry& e : play_) {
      if (!e.problem.empty()) throw UserError(e.problem);
      chunks.push_back(&e);
    }
  }
  // On every core: loading is dominated by the kernel handing the process fresh pages for every
  // sample's vectors (about 180,000 page faults for 100 camera episodes), which parallelises;
  // HDF5 serialises its own calls internally.
  const unsigned threads = std::max(1u, std::thread::hardware_concurrency());
  dataset.demos.resize(demos.size());
  ParallelFor(demos.size(), threads, [&](size_t i) {
    dataset.demos[i] = ReadDemoFile(demos[i]->path, manifest_).episode;
  });
  std::vector<std::vector<PlaySample>> play(chunks.size());
  ParallelFor(chunks.size(), threads,
              [&](size_t i) { play[i] = ReadPlayFile(chunks[i]->path, manifest_).samples; });
  for (std::vector<PlaySample>& chunk : play) {
    dataset.play_chunks.push_back(static_cast<int>(chunk.size()));
    for (PlaySample& sample : chunk) dataset.play.push_back(std::move(sample));
  }
  return dataset;
}

double Session::DemoSeconds(bool include_bad) const {
  double total = 0;
  for (const EpisodeEntry& e : demos_) {
    if (include_bad || !e.flags.bad) total += e.meta.teaching_seconds;
  }
  return total;
}

double Session::PlaySeconds() const {
  double total = 0;
  for (const EpisodeEntry& e : play_) total += e.meta.teaching_seconds;
  return total;
}

}  // namespace recon::store
