#include "app/studio/recent_sessions.h"

#include <cstdlib>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <system_error>

#include "engine/core/files.h"

namespace recon::studio {

namespace fs = std::filesystem;

std::string RecentSessions::DefaultPath() {
  const char* config = std::getenv("XDG_CONFIG_HOME");
  const char* home = std::getenv("HOME");
  const fs::path base = config != nullptr && *config != '\0' ? fs::path(config)
                        : home != nullptr                    ? fs::path(home) / ".config"
                                                             : fs::temp_directory_path();
  return (base / "recon-studio" / "recent.json").string();
}

RecentSessions::RecentSessions(std::string path) : path_(std::move(path)) {
  const std::optional<std::string> text = ReadWholeFile(path_);
  if (!text) return;
  try {
    const nlohmann::json j = nlohmann::json::parse(*text);
    if (!j.is_object() || !j.contains("sessions") || !j["sessions"].is_array()) {
      throw std::runtime_error("it has no \"sessions\" list");
    }
    for (const nlohmann::json& entry : j["sessions"]) {
      if (!entry.is_string()) throw std::runtime_error("an entry of \"sessions\" is not a string");
      if (entries_.size() < kMaxEntries) entries_.push_back(entry.get<std::string>());
    }
  } catch (const std::exception& e) {
    entries_.clear();
    std::error_code ignored;
    fs::rename(path_, path_ + ".corrupt", ignored);
    problem_ = "the list of recent sessions " + path_ + " is unreadable (" + e.what() +
               "); it was moved to " + path_ + ".corrupt and a new list is started";
  }
}

std::vector<std::string> RecentSessions::Openable() const {
  std::vector<std::string> openable;
  for (const std::string& dir : entries_) {
    std::error_code error;
    if (std::filesystem::is_regular_file(std::filesystem::path(dir) / "session.json", error)) {
      openable.push_back(dir);
    }
  }
  return openable;
}

std::string RecentSessions::Add(const std::string& dir) {
  std::error_code ec;
  const std::string absolute = fs::weakly_canonical(fs::absolute(dir), ec).string();
  const std::string entry = ec ? dir : absolute;
  std::erase(entries_, entry);
  entries_.insert(entries_.begin(), entry);
  if (entries_.size() > kMaxEntries) entries_.resize(kMaxEntries);
  try {
    fs::create_directories(fs::path(path_).parent_path());
    WriteFileAtomically(path_, nlohmann::json{{"sessions", entries_}}.dump(1) + "\n");
  } catch (const std::exception& e) {
    return "cannot remember the recent sessions in " + path_ + ": " + e.what();
  }
  return "";
}

}  // namespace recon::studio
