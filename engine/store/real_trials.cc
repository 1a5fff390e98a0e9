#include "engine/store/real_trials.h"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "engine/core/error.h"
#include "engine/store/atomic_file.h"
#include "engine/store/h5.h"
#include "engine/store/json_fields.h"

namespace recon::store {

namespace {

using json = nlohmann::json;

constexpr char kFramesKind[] = "trial_frames";
constexpr int64_t kFramesFormat = 1;

/// Rows of one size each, as a row-major block.
std::vector<float> Block(const std::vector<std::vector<float>>& rows, const std::string& what,
                         size_t* width) {
  *width = rows.empty() ? 0 : rows.front().size();
  std::vector<float> block;
  block.reserve(rows.size() * *width);
  for (size_t i = 0; i < rows.size(); ++i) {
    if (rows[i].size() != *width) {
      throw UserError("trial frames: " + what + " row " + std::to_string(i) + " has " +
                      std::to_string(rows[i].size()) + " values, the first " +
                      std::to_string(*width));
    }
    block.insert(block.end(), rows[i].begin(), rows[i].end());
  }
  return block;
}

std::vector<std::vector<float>> Rows(const std::vector<float>& block, size_t rows, size_t width) {
  std::vector<std::vector<float>> out(rows);
  for (size_t i = 0; i < rows; ++i) {
    out[i].assign(block.begin() + static_cast<std::ptrdiff_t>(i * width),
                  block.begin() + static_cast<std::ptrdiff_t>((i + 1) * width));
  }
  return out;
}

}  // namespace

int RealTrialLog::successes() const {
  int n = 0;
  for (const RealTrial& t : trials) n += t.succeeded;
  return n;
}

double RealTrialLog::success_rate() const {
  return trials.empty() ? 0.0 : static_cast<double>(successes()) / trials.size();
}

json RealTrialLogToJson(const RealTrialLog& log) {
  json trials = json::array();
  for (const RealTrial& t : log.trials) {
    json layout = json::object();
    for (const auto& [object, xy] : t.layout) layout[object] = {xy[0], xy[1]};
    trials.push_back({{"number", t.number},
                      {"scene_seed", t.scene_seed},
                      {"layout", layout},
                      {"succeeded", t.succeeded},
                      {"reason", t.reason},
                      {"stopped", t.stopped},
                      {"steps", t.steps},
                      {"seconds", t.seconds},
                      {"frames", t.frames ? json(*t.frames) : json(nullptr)},
                      {"judged_at", t.judged_at}});
  }
  return {{"method", log.method},
          {"label", log.label},
          {"model_id", log.model_id ? json(*log.model_id) : json(nullptr)},
          {"cell", log.cell},
          {"successes", log.successes()},
          {"success_rate", log.success_rate()},
          {"trials", trials}};
}

RealTrialLog RealTrialLogFromJson(const json& value, const std::string& source,
                                  const std::string& method) {
  const FieldReader top(value, source, "");
  RealTrialLog log;
  log.method = top.OptionalString("method", method);
  log.label = top.OptionalString("label", log.method);
  log.model_id = top.OptionalNullableString("model_id");
  log.cell = top.OptionalString("cell", "");
  const json& rows = top.Array("trials");
  for (size_t i = 0; i < rows.size(); ++i) {
    const FieldReader row = top.Element(rows[i], "trials", i);
    RealTrial t;
    t.number = static_cast<int>(row.Integer("number"));
    if (t.number != static_cast<int>(i) + 1) {
      throw UserError(source + ": " + row.Name("number") + ": trial " + std::to_string(t.number) +
                      " where trial " + std::to_string(i + 1) + " was expected");
    }
    t.scene_seed = row.OptionalUnsigned("scene_seed", 0);
    if (row.Has("layout")) {
      const FieldReader layout = row.Object("layout");
      for (const auto& [object, xy] : layout.object().items()) {
        if (!xy.is_array() || xy.size() != 2 || !xy[0].is_number() || !xy[1].is_number()) {
          throw UserError(source + ": " + layout.Name(object) + ": expected [x, y] in metres");
        }
        t.layout[object] = {xy[0].get<double>(), xy[1].get<double>()};
      }
    }
    t.succeeded = row.Boolean("succeeded", false);
    t.reason = row.OptionalString("reason", "");
    t.stopped = row.Boolean("stopped", false);
    t.steps = static_cast<int>(row.OptionalInteger("steps", 0));
    t.seconds = row.OptionalNumberOrNan("seconds", 0.0);
    t.frames = row.OptionalNullableString("frames");
    if (t.frames) {
      const std::filesystem::path p(*t.frames);
      if (p.is_absolute() || p.lexically_normal().string().rfind("..", 0) == 0) {
        throw UserError(source + ": " + row.Name("frames") + ": \"" + *t.frames +
                        "\" is not a path inside the session");
      }
    }
    t.judged_at = row.OptionalString("judged_at", "");
    log.trials.push_back(std::move(t));
  }
  return log;
}

void WriteRealTrialLog(const std::string& path, const RealTrialLog& log) {
  std::filesystem::create_directories(std::filesystem::path(path).parent_path());
  WriteJsonFile(path, RealTrialLogToJson(log));
}

std::optional<RealTrialLog> ReadRealTrialLog(const Session& session, const std::string& method) {
  return ReadRecordFile(session.RealTrialsPath(method), method, &RealTrialLogFromJson);
}

std::map<std::string, RealTrialLog> ReadRealTrialLogs(const Session& session) {
  return ReadRecordsIn((std::filesystem::path(session.dir()) / Session::kTrialFolder).string(),
                       &RealTrialLogFromJson);
}

void WriteTrialFrames(const std::string& path, const TrialFrames& frames) {
  const size_t steps = frames.y.size();
  if (frames.x.size() != steps || frames.u.size() != steps) {
    throw UserError("trial frames: " + std::to_string(frames.x.size()) + " states, " +
                    std::to_string(steps) + " images and " + std::to_string(frames.u.size()) +
                    " actions; one of each per step");
  }
  size_t x_width = 0, y_width = 0, u_width = 0;
  const std::vector<float> x = Block(frames.x, "x", &x_width);
  const std::vector<float> y = Block(frames.y, "y", &y_width);
  const std::vector<float> u = Block(frames.u, "u", &u_width);
  const size_t s = static_cast<size_t>(frames.image_size);
  if (frames.image_size < 1 || (steps > 0 && y_width != 3 * s * s)) {
    throw UserError("trial frames: an image of " + std::to_string(y_width) + " values is not 3 x " +
                    std::to_string(frames.image_size) + " x " + std::to_string(frames.image_size));
  }
  std::vector<uint8_t> bytes(y.size());
  for (size_t i = 0; i < y.size(); ++i) {
    bytes[i] = static_cast<uint8_t>(std::lround(std::clamp(y[i], 0.0f, 255.0f)));
  }
  std::filesystem::create_directories(std::filesystem::path(path).parent_path());
  WriteFileVia(path, Durability::kFsync, [&](const std::string& tmp) {
    h5::File file = h5::File::Create(tmp);
    const hid_t root = file.id();
    h5::WriteAttribute(file, root, "recon_kind", std::string(kFramesKind));
    h5::WriteAttribute(file, root, "recon_format", kFramesFormat);
    h5::WriteAttribute(file, root, "image_size", static_cast<int64_t>(frames.image_size));
    h5::WriteArray(file, root, "x", h5::ElementType::kFloat32, {steps, x_width}, x.data());
    h5::WriteArray(file, root, "y", h5::ElementType::kUInt8, {steps, y_width}, bytes.data());
    h5::WriteArray(file, root, "u", h5::ElementType::kFloat32, {steps, u_width}, u.data());
    file.Close();  // built in memory: this writes it
  });
}

TrialFrames ReadTrialFrames(const std::string& path) {
  const h5::File file = h5::File::OpenReadOnly(path);
  const hid_t root = file.id();
  const std::string kind = h5::ReadStringAttribute(file, root, "recon_kind");
  if (kind != kFramesKind) {
    h5::Fail(path, "attribute 'recon_kind' is \"" + kind + "\": this is not a trial's frames");
  }
  const int64_t format = h5::ReadIntAttribute(file, root, "recon_format");
  if (format != kFramesFormat) {
    h5::Fail(path, "attribute 'recon_format' is " + std::to_string(format) +
                       "; this program reads trial frames of format " +
                       std::to_string(kFramesFormat));
  }
  TrialFrames frames;
  frames.image_size = static_cast<int>(h5::ReadIntAttribute(file, root, "image_size"));
  const std::vector<hsize_t> y_dims = h5::Dimensions(file, root, "y");
  const std::vector<hsize_t> x_dims = h5::Dimensions(file, root, "x");
  const std::vector<hsize_t> u_dims = h5::Dimensions(file, root, "u");
  const size_t s = static_cast<size_t>(std::max(frames.image_size, 0));
  if (y_dims.size() != 2 || x_dims.size() != 2 || u_dims.size() != 2 || x_dims[0] != y_dims[0] ||
      u_dims[0] != y_dims[0] || (y_dims[0] > 0 && y_dims[1] != 3 * s * s)) {
    h5::Fail(path, "its x, y and u do not have one row per step of the sizes it states");
  }
  const std::vector<uint8_t> bytes = h5::ReadBytes(file, root, "y");
  frames.y = Rows(std::vector<float>(bytes.begin(), bytes.end()), y_dims[0], y_dims[1]);
  frames.x = Rows(h5::ReadFloats(file, root, "x"), x_dims[0], x_dims[1]);
  frames.u = Rows(h5::ReadFloats(file, root, "u"), u_dims[0], u_dims[1]);
  return frames;
}

}  // namespace recon::store
