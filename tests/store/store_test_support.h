#pragma once

// Synthetic sessions for the store tests: small shapes, deterministic values, both y encodings.

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>

#include "engine/core/error.h"
#include "engine/core/rng.h"
#include "engine/store/episode_file.h"
#include "engine/store/manifest.h"

namespace recon::store::testing {

/// A fresh empty folder under the system temp dir, removed when the object goes.
class TempDir {
 public:
  explicit TempDir(const std::string& name)
      : path_(std::filesystem::temp_directory_path() /
              ("recon-store-" + name + "-" + std::to_string(getpid()))) {
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  std::string Path(const std::string& relative = "") const {
    return relative.empty() ? path_.string() : (path_ / relative).string();
  }

 private:
  std::filesystem::path path_;
};

/// The message of the UserError `f` throws, or "(no error)".
inline std::string ErrorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const UserError& e) {
    return e.what();
  }
  return "(no error)";
}

/// The file's bytes ("" if it cannot be read).
inline std::string Bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

/// Writes `text` as the whole of `path`, making its folder if needed.
inline void WriteText(const std::string& path, const std::string& text) {
  std::filesystem::create_directories(std::filesystem::path(path).parent_path());
  std::ofstream(path, std::ios::binary) << text;
}

/// x 2, y 3x4x5 image, beacons "red" (2) and "dist" (1), u 2.
inline SessionManifest SmallManifest(const std::string& y_encoding = "uint8") {
  SessionManifest m;
  m.created_at = "2026-11-22T00:00:00Z";
  m.created_by = "store test";
  m.world = "synthetic";
  m.cell = "simulated";
  m.placement = "exact";
  m.step_seconds = 0.1;
  m.devices = {{"camera", "simulated", "4x5"}};
  m.beacons = {{"red", "the red object", "position", 2, "m"},
               {"dist", "the red object", "distance", 1, "m"}};
  m.spec.x_dim = 2;
  m.spec.y_shape = {3, 4, 5};
  m.spec.b_dim = 3;
  m.spec.u_dim = 2;
  m.y_encoding = y_encoding;
  m.seed = 7;
  return m;
}

/// A demonstration of `n` samples whose values follow from `seed`; integral pixels for uint8.
inline DemoRecord SyntheticDemo(int n, uint64_t seed, bool integral_pixels = true) {
  Rng rng(seed);
  DemoRecord record;
  record.meta.seed = seed;
  record.meta.source = "synthetic";
  record.meta.teaching_seconds = 0.1 * n;
  record.meta.succeeded = true;
  for (int i = 0; i < n; ++i) {
    Sample s;
    s.x = {static_cast<float>(rng.Uniform(-1, 1)), static_cast<float>(rng.Uniform(-1, 1))};
    for (int p = 0; p < 3 * 4 * 5; ++p) {
      const double v = rng.Uniform(0, 255);
      s.y.push_back(integral_pixels ? static_cast<float>(static_cast<int>(v))
                                    : static_cast<float>(v));
    }
    s.b = {static_cast<float>(rng.Normal()), static_cast<float>(rng.Normal()),
           static_cast<float>(rng.Uniform(0, 2))};
    s.u = {static_cast<float>(rng.Normal()), static_cast<float>(rng.Normal())};
    record.episode.samples.push_back(s);
    record.rewards.push_back(i + 1 == n ? 1.0 : 0.0);
  }
  return record;
}

inline PlayRecord SyntheticPlay(int n, uint64_t seed) {
  const DemoRecord demo = SyntheticDemo(n, seed);
  PlayRecord record;
  record.meta.seed = seed;
  record.meta.source = "synthetic-play";
  record.meta.teaching_seconds = 0.1 * n;
  for (const Sample& s : demo.episode.samples) record.samples.push_back({s.x, s.y, s.b});
  return record;
}

}  // namespace recon::store::testing
