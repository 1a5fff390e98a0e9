#pragma once

#include <string>
#include <vector>

namespace recon::studio {

/// The sessions the studio opened lately, most recent first, kept in
/// $XDG_CONFIG_HOME/recon-studio/recent.json (~/.config/... without it) so the Session menu can
/// offer them on the next start.
class RecentSessions {
 public:
  static constexpr size_t kMaxEntries = 8;

  /// Where the list lives on this machine.
  static std::string DefaultPath();

  /// Reads the list at `path` (none yet: empty). A file that is not such a list is moved aside
  /// to `<path>.corrupt` and `problem()` says so, naming the file; the studio starts anyway.
  explicit RecentSessions(std::string path);

  const std::vector<std::string>& entries() const { return entries_; }
  /// The entries that still hold a session (a session.json), for the menu and the picker: one
  /// deleted since, or a temporary folder gone, is not offered (it stays in the file, in case
  /// its disk comes back).
  std::vector<std::string> Openable() const;
  const std::string& problem() const { return problem_; }
  /// Puts `dir` (made absolute) first and writes the list atomically. Failing to write it is
  /// not worth stopping a teacher for: the reason is returned (empty on success).
  std::string Add(const std::string& dir);

 private:
  std::string path_;
  std::vector<std::string> entries_;
  std::string problem_;
};

}  // namespace recon::studio
