#include "app/cli/result_staleness.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <vector>

#include "engine/core/digest.h"
#include "engine/core/error.h"
#include "engine/core/files.h"
#include "engine/core/strings.h"

namespace recon::cli {

namespace {

// At most this many names are listed; the rest are counted.
constexpr size_t kNamesListed = 5;

std::string NameList(const std::vector<std::string>& names) {
  std::vector<std::string> shown(names.begin(),
                                 names.begin() + std::min(names.size(), kNamesListed));
  std::string text = JoinNames(shown);
  if (names.size() > kNamesListed) {
    text += " and " + std::to_string(names.size() - kNamesListed) + " more";
  }
  return text;
}

// a - b, in a's order.
std::vector<std::string> Missing(const std::vector<std::string>& a,
                                 const std::vector<std::string>& b) {
  std::vector<std::string> out;
  for (const std::string& name : a) {
    if (std::find(b.begin(), b.end(), name) == b.end()) out.push_back(name);
  }
  return out;
}

// "4 demonstrations and 2 play chunks".
std::string Counted(const std::vector<std::string>& names) {
  const auto play = static_cast<size_t>(std::count_if(
      names.begin(), names.end(), [](const std::string& n) { return n.rfind("play_", 0) == 0; }));
  const size_t demos = names.size() - play;
  std::string text = std::to_string(demos) + (demos == 1 ? " demonstration" : " demonstrations");
  if (play > 0) {
    text += " and " + std::to_string(play) + (play == 1 ? " play chunk" : " play chunks");
  }
  return text;
}

constexpr const char* kCheckpointIdPrefix = "fnv1a:";

bool IsCheckpointId(const std::optional<std::string>& id) {
  return id && id->rfind(kCheckpointIdPrefix, 0) == 0;
}

// The id of the checkpoint a record names (relative to the session).
std::string IdOfNamedCheckpoint(const store::Session& session, const std::string& relative) {
  if (relative.empty()) return "";
  return CheckpointModelId((std::filesystem::path(session.dir()) / relative).string());
}

}  // namespace

std::string CheckpointModelId(const std::string& path) {
  // A checkpoint that is not a readable file has no id; its reader names what is wrong with it.
  try {
    RefuseNonRegularFile(path);
  } catch (const UserError&) {
    return "";
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) return "";
  uint64_t hash = kFnv1aOffset;
  char buffer[1 << 16];
  while (in.read(buffer, sizeof(buffer)) || in.gcount() > 0) {
    hash = Fnv1a(buffer, static_cast<size_t>(in.gcount()), hash);
  }
  return kCheckpointIdPrefix + DigestHex(hash);
}

std::string TrainingStaleness(const store::Session& session,
                              const store::TrainingRecord& training) {
  if (IsCheckpointId(training.model_id)) {
    const std::string now = IdOfNamedCheckpoint(session, training.checkpoint);
    if (now.empty()) return "its model " + training.checkpoint + " is gone or unreadable: retrain";
    if (now != *training.model_id) {
      return training.checkpoint +
             " holds another model than this record describes (a training stopped after saving "
             "its model and before its record): retrain";
    }
  }
  if (!training.trained_on) return "";
  const store::TrainedOn& on = *training.trained_on;
  store::DatasetOptions options;
  options.split = store::Split::kTrain;
  options.include_bad = on.include_bad;
  options.include_play = on.use_play;
  const std::vector<std::string>& then = on.episodes;
  const std::vector<std::string> now = session.DatasetEpisodeNames(options);
  if (then == now) return "";
  const std::vector<std::string> added = Missing(now, then);
  const std::vector<std::string> gone = Missing(then, now);
  std::string why = "trained on " + Counted(then) + "; since then ";
  if (!added.empty()) {
    why += NameList(added) + (added.size() == 1 ? " was" : " were") + " added to the training set";
  }
  if (!gone.empty()) {
    why += std::string(added.empty() ? "" : ", and ") + NameList(gone) +
           (gone.size() == 1 ? " has" : " have") +
           " left it (deleted, marked bad or moved to the validation split)";
  }
  return why + ": retrain to use the session as it is";
}

std::string RolloutStaleness(const store::Session& session, const store::RolloutSummary& rollouts,
                             const std::optional<store::TrainingRecord>& training) {
  if (!rollouts.model_id) return "";  // from before model ids: nothing to compare
  if (IsCheckpointId(rollouts.model_id)) {
    const std::string now = IdOfNamedCheckpoint(session, rollouts.checkpoint);
    if (now.empty()) return "the model these rollouts are of is gone or unreadable: retrain";
    if (now != *rollouts.model_id) {
      return "the model was retrained after these rollouts: roll it out again";
    }
  } else {
    if (!training) return "the model these rollouts are of is gone or unreadable: retrain";
    if (training->model_id != rollouts.model_id) {
      return "the model was retrained after these rollouts: roll it out again";
    }
  }
  if (!training || TrainingStaleness(session, *training).empty()) return "";
  return "rolled out with a model of the session as it was (see its training): retrain and roll "
         "out again";
}

std::string TrialStaleness(const store::Session& session, const store::RealTrialLog& trials) {
  if (!trials.model_id) return "";
  const std::string now = CheckpointModelId(session.CheckpointPath(trials.method));
  if (now.empty()) return "the model these trials ran is gone or unreadable: retrain";
  if (now != *trials.model_id) return "the model was retrained after these trials";
  return "";
}

SessionResults ReadSessionResults(const store::Session& session) {
  SessionResults results;
  for (auto& [method, record] : store::ReadTrainingRecords(session)) {
    std::string why = TrainingStaleness(session, record);
    results.training[method] = {std::move(record), std::move(why)};
  }
  for (auto& [method, summary] : store::ReadRolloutSummaries(session)) {
    const auto trained = results.training.find(method);
    std::string why = RolloutStaleness(session, summary,
                                       trained == results.training.end()
                                           ? std::nullopt
                                           : std::make_optional(trained->second.record));
    results.rollouts[method] = {std::move(summary), std::move(why)};
  }
  for (auto& [method, log] : store::ReadRealTrialLogs(session)) {
    std::string why = TrialStaleness(session, log);
    results.trials[method] = {std::move(log), std::move(why)};
  }
  return results;
}

}  // namespace recon::cli
