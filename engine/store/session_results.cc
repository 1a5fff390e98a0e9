// Where a session keeps what was made from its episodes, one file of each kind per method: the
// model, its training record, its rollouts' summary and their replay; what the probe found; and
// its report.

#include <filesystem>

#include "engine/store/session.h"

namespace recon::store {

std::string Session::CheckpointRelativePath(const std::string& method) {
  return (std::filesystem::path(kCheckpointFolder) / (method + ".ckpt")).string();
}

std::string Session::TrainingRecordRelativePath(const std::string& method) {
  return (std::filesystem::path(kTrainingFolder) / (method + ".json")).string();
}

std::string Session::RolloutSummaryRelativePath(const std::string& method) {
  return (std::filesystem::path(kRolloutFolder) / (method + ".json")).string();
}

std::string Session::RolloutReplayRelativePath(const std::string& method) {
  return (std::filesystem::path(kRolloutFolder) / (method + ".replay.h5")).string();
}

std::string Session::CheckpointPath(const std::string& method) const {
  return Path(CheckpointRelativePath(method));
}

std::string Session::TrainingRecordPath(const std::string& method) const {
  return Path(TrainingRecordRelativePath(method));
}

std::string Session::RolloutSummaryPath(const std::string& method) const {
  return Path(RolloutSummaryRelativePath(method));
}

std::string Session::RolloutReplayPath(const std::string& method) const {
  return Path(RolloutReplayRelativePath(method));
}

std::string Session::RealTrialsPath(const std::string& method) const {
  return Path((std::filesystem::path(kTrialFolder) / (method + ".json")).string());
}

std::string Session::TrialFramesRelativePath(const std::string& method, int number) {
  return (std::filesystem::path(kTrialFolder) / method /
          ("trial_" + std::to_string(number) + ".h5"))
      .string();
}

std::string Session::TrialFramesPath(const std::string& method, int number) const {
  return Path(TrialFramesRelativePath(method, number));
}

std::string Session::ProbeSummaryPath() const {
  return Path((std::filesystem::path(kProbeFolder) / "probe.json").string());
}

std::string Session::ProbeFigureRelativePath(const std::string& method, const std::string& object) {
  return (std::filesystem::path(kProbeFolder) / (method + "_" + object + ".png")).string();
}

std::string Session::ProbeFigurePath(const std::string& method, const std::string& object) const {
  return Path(ProbeFigureRelativePath(method, object));
}

std::string Session::SaliencySheetPath(const std::string& episode) const {
  return Path((std::filesystem::path(kProbeFolder) / ("saliency_" + episode + ".png")).string());
}

std::string Session::ReportFolder() const { return Path("report"); }

std::string Session::ReportPath() const {
  return (std::filesystem::path(ReportFolder()) / "report.html").string();
}

}  // namespace recon::store
