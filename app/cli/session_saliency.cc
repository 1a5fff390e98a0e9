#include "app/cli/session_saliency.h"

#include <algorithm>
#include <filesystem>

#include "app/cli/session_probe.h"
#include "engine/core/error.h"
#include "engine/core/files.h"
#include "engine/core/image.h"
#include "engine/learn/learner.h"
#include "engine/probe/saliency.h"
#include "engine/report/image_png.h"
#include "engine/store/episode_file.h"

namespace recon::cli {

namespace fs = std::filesystem;

namespace {

constexpr int kMaxFrames = 64;
constexpr int kScale = 3;  // a 64 x 64 frame is drawn 192 x 192
constexpr int kGap = 4;

/// Copies `tile` into `sheet` at (left, top), each pixel kScale x kScale.
void Place(const RgbImage& tile, int left, int top, RgbImage& sheet) {
  for (int r = 0; r < tile.height * kScale; ++r) {
    for (int c = 0; c < tile.width * kScale; ++c) {
      const uint8_t* from = tile.Pixel(r / kScale, c / kScale);
      uint8_t* to = sheet.rgb.data() + (static_cast<size_t>(top + r) * sheet.width + left + c) * 3;
      std::copy_n(from, 3, to);
    }
  }
}

}  // namespace

SaliencySheet WriteSaliencySheet(const store::Session& session,
                                 const SaliencySheetOptions& options) {
  if (options.frames < 1 || options.frames > kMaxFrames) {
    throw UserError("a saliency sheet has 1 to " + std::to_string(kMaxFrames) + " frames, got " +
                    std::to_string(options.frames));
  }
  bool known = false;
  std::string demos;
  for (const store::EpisodeEntry& e : session.demos()) {
    known |= e.name == options.episode;
    demos += (demos.empty() ? "" : ", ") + e.name;
  }
  if (!known) {
    throw UserError("the session has no demonstration \"" + options.episode + "\" (valid: " +
                    (demos.empty() ? "none recorded yet" : demos) + "); nothing was written");
  }
  const std::vector<std::string> methods =
      TrainedMethods(session, options.methods, "to draw a saliency of");
  std::vector<learn::Policy> policies;
  SaliencySheet sheet;
  sheet.rows.push_back("recorded");
  for (const std::string& method : methods) {
    policies.push_back(learn::LoadPolicy(session.CheckpointPath(method)));
    sheet.rows.push_back(MethodLabel(session, method));
  }
  const store::DemoRecord demo = session.ReadDemo(options.episode);
  const std::vector<Sample>& samples = demo.episode.samples;
  const std::vector<int64_t>& shape = session.manifest().spec.y_shape;
  if (shape.size() != 3 || samples.empty()) {
    throw UserError(
        "the session's observations are no camera images: nothing to draw a "
        "saliency on; nothing was written");
  }
  const int size = static_cast<int>(shape[2]);
  const int columns = std::min<int>(options.frames, static_cast<int>(samples.size()));
  for (int c = 0; c < columns; ++c) {
    sheet.steps.push_back(columns == 1 ? 0
                                       : static_cast<int>(static_cast<int64_t>(c) *
                                                          (samples.size() - 1) / (columns - 1)));
  }
  const int tile = size * kScale;
  RgbImage image{
      columns * tile + (columns + 1) * kGap,
      static_cast<int>(sheet.rows.size()) * tile + (static_cast<int>(sheet.rows.size()) + 1) * kGap,
      {}};
  image.rgb.assign(static_cast<size_t>(image.width) * image.height * 3, 255);
  for (int c = 0; c < columns; ++c) {
    const Sample& sample = samples[static_cast<size_t>(sheet.steps[static_cast<size_t>(c)])];
    const RgbImage frame = ImageFromObservation(sample.y, size);
    const int left = kGap + c * (tile + kGap);
    Place(frame, left, kGap, image);
    for (size_t m = 0; m < policies.size(); ++m) {
      const probe::SaliencyMap map = options.occlusion
                                         ? probe::OcclusionSaliency(policies[m], sample.x, sample.y)
                                         : probe::GradientSaliency(policies[m], sample.x, sample.y);
      Place(probe::OverlaySaliency(frame, map), left,
            kGap + static_cast<int>(m + 1) * (tile + kGap), image);
    }
  }
  sheet.path = session.SaliencySheetPath(options.episode);
  EnsureWritableDirectory(fs::path(sheet.path).parent_path().string());
  report::WritePng(image, sheet.path);
  return sheet;
}

}  // namespace recon::cli
