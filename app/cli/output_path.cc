#include "app/cli/output_path.h"

#include <filesystem>
#include <system_error>

#include "engine/core/error.h"
#include "engine/store/session.h"

namespace recon::cli {

namespace fs = std::filesystem;

std::optional<std::string> EnclosingSession(const std::string& path) {
  std::error_code ec;
  fs::path at = fs::weakly_canonical(fs::absolute(path, ec), ec);
  if (ec) return std::nullopt;
  for (; !at.empty(); at = at.parent_path()) {
    if (store::Session::Exists(at.string())) return at.string();
    if (at == at.root_path()) break;
  }
  return std::nullopt;
}

void CheckOutputFile(const std::string& option, const std::string& path, bool force) {
  if (path.empty()) throw UserError(option + ": give a file to write");
  if (const std::optional<std::string> session = EnclosingSession(path)) {
    throw UserError(option + " " + path + " is inside the teaching session " + *session +
                    ", whose files only the session's own commands write; choose a path "
                    "outside it");
  }
  std::error_code ec;
  if (fs::is_directory(path, ec)) {
    throw UserError(option + " " + path + " is a folder; give a file name");
  }
  if (!force && fs::exists(path, ec)) {
    throw UserError(option + " " + path +
                    " already exists; nothing was written (add --force to replace it)");
  }
}

void CheckOutputFolder(const std::string& option, const std::string& path, bool force,
                       const std::string& marker, const std::string& allowed_inside) {
  std::error_code ec;
  const bool is_allowed =
      !allowed_inside.empty() && fs::weakly_canonical(fs::absolute(path), ec) ==
                                     fs::weakly_canonical(fs::absolute(allowed_inside), ec);
  if (!is_allowed) {
    if (const std::optional<std::string> session = EnclosingSession(path)) {
      throw UserError(option + " " + path + " is inside the teaching session " + *session +
                      ", whose files only the session's own commands write; choose a folder "
                      "outside it");
    }
  }
  if (fs::exists(path, ec) && !fs::is_directory(path, ec)) {
    throw UserError(option + " " + path + " is a file, not a folder");
  }
  // Writing again rewrites its own earlier output; any other folder with files in it is the
  // user's.
  if (!force && fs::is_directory(path, ec) && !fs::is_empty(path, ec) &&
      !fs::exists(fs::path(path) / marker, ec)) {
    throw UserError(option + " " + path + " holds other files (no " + marker +
                    " from an earlier run); nothing was written (choose a new or empty folder, or "
                    "add --force to write into it)");
  }
}

void AddForceFlag(CLI::App& command, bool& force) {
  command.add_flag("--force", force, "replace an existing output file");
}

}  // namespace recon::cli
