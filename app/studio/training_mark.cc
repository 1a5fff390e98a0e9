#include "app/studio/training_mark.h"

#include <ctime>
#include <filesystem>
#include <optional>

#include "engine/core/files.h"

namespace recon::studio {

namespace {

namespace fs = std::filesystem;

// Beside session.json; no reader of sessions looks for it (engine/store lists episodes by their
// folders), so a session written before it existed reads the same.
constexpr char kNoteName[] = "training.running";

std::string NotePath(const std::string& session_dir) {
  return (fs::path(session_dir) / kNoteName).string();
}

std::string Joined(const std::vector<std::string>& labels) {
  std::string out;
  for (size_t i = 0; i < labels.size(); ++i) {
    if (i > 0) out += i + 1 == labels.size() ? " and " : ", ";
    out += labels[i];
  }
  return out;
}

}  // namespace

void NoteTrainingStarted(const std::string& session_dir, const std::vector<std::string>& labels,
                         int steps) {
  const std::time_t now = std::time(nullptr);
  char started[32] = "";
  std::strftime(started, sizeof(started), "%Y-%m-%d %H:%M", std::localtime(&now));
  // One line, what the studio shows: the note is read by people too (ls of a session).
  std::string what = "The training of " + Joined(labels);
  if (steps > 0) what += " (" + std::to_string(steps) + " steps)";
  WriteFileAtomically(NotePath(session_dir), what + ", started " + started + "\n");
}

void NoteTrainingEnded(const std::string& session_dir) {
  std::error_code ignored;  // none there is what is wanted
  fs::remove(NotePath(session_dir), ignored);
}

std::string TrainingCutShort(const std::string& session_dir) {
  std::optional<std::string> note = ReadWholeFile(NotePath(session_dir));
  if (!note) return "";
  while (!note->empty() && (note->back() == '\n' || note->back() == '\r')) note->pop_back();
  if (note->empty()) *note = "The last training";
  return *note +
         ", was cut short when the studio closed: the models shown are the ones saved before "
         "it. Train again to have it.";
}

}  // namespace recon::studio
