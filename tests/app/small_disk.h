#pragma once

// A small file system for full-disk tests of the real binaries (DiskFullTest, StudioDiskFullTest):
// a tmpfs mounted in a private mount namespace (nothing outside the test sees it) holding a copy
// of a session, the test's extra inputs and a filler file that leaves a given number of bytes
// free. Needs root or a user namespace, as the machines this project runs on give.

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>
#include <vector>

#include "tests/app/run_recon.h"
#include "tests/app/saved_files.h"

namespace recon::testing {

/// How much to leave free in a walk of a program that writes `written` bytes with room to
/// spare: nothing, one page, 1/8 to 7/8 of it and, for each of `short_by`, that much short of
/// the whole (where the last files are written), in whole pages.
inline std::set<uint64_t> FreeSizesToWalk(uint64_t written,
                                          const std::vector<uint64_t>& short_by = {}) {
  constexpr uint64_t kPageBytes = 4096;
  std::set<uint64_t> sizes = {0, kPageBytes};
  for (int eighth = 1; eighth < 8; ++eighth) {
    sizes.insert(written * eighth / 8 / kPageBytes * kPageBytes);
  }
  for (const uint64_t bytes : short_by) {
    if (written > bytes) sizes.insert((written - bytes) / kPageBytes * kPageBytes);
  }
  return sizes;
}

/// What a run on the small file system left: its copy, the program's output and exit code.
struct FullDiskRun {
  CommandResult result;
  std::filesystem::path root;  ///< a copy of the small file system after the run, filler removed
};

/// One small file system: the session at ROOT/s (or nothing there, for a program that creates
/// it) and whatever `extra` holds at ROOT/extra.
class SmallDisk {
 public:
  /// `program` is the command run, with its environment before it if any (e.g.
  /// "HOME=@R/home /path/recon-studio"); @R in it is the small file system's root.
  SmallDisk(std::filesystem::path session, std::filesystem::path extra, std::filesystem::path work,
            std::string program = RECON_CLI)
      : session_(std::move(session)),
        extra_(std::move(extra)),
        work_(std::move(work)),
        program_(std::move(program)) {}

  /// Room beyond the copies, so that the filler, not the mount's size, decides what is free.
  static constexpr uint64_t kPlentyBytes = 96ull << 20;

  /// Runs the program with `args` and `free_bytes` left free after `prepare` (a shell line run
  /// in the small file system first). In `args` and `prepare`, @S is the session and @R the root.
  FullDiskRun Run(const std::string& args, uint64_t free_bytes, const std::string& prepare = "",
                  const std::string& label = "") {
    namespace fs = std::filesystem;
    const fs::path out = work_ / ("run_" + label + std::to_string(runs_++));
    fs::remove_all(out);
    const fs::path script = work_ / "run.sh";
    std::ofstream(script) << R"sh(set -u
m=$(mktemp -d /tmp/recon_disk_full.XXXXXX)
trap 'umount "$m" 2>/dev/null; rmdir "$m" 2>/dev/null' EXIT
mount -t tmpfs -o size=$SIZE tmpfs "$m" || { echo "cannot mount a tmpfs (the test needs root or a user namespace)"; exit 90; }
if [ -n "$SESSION" ]; then cp -a "$SESSION" "$m/s"; fi
if [ -d "$EXTRA" ]; then cp -a "$EXTRA" "$m/extra"; fi
sub() { local t=${1//@S/$m/s}; echo "${t//@R/$m}"; }
eval "$(sub "$PREPARE")"
avail=$(( $(stat -f -c '%a*%S' "$m") ))
if [ "$avail" -gt "$FREE" ]; then fallocate -l $(( avail - FREE )) "$m/filler" || exit 91; fi
eval "$(sub "$PROGRAM") $(sub "$ARGS")" > "$OUT.output" 2>&1
echo $? > "$OUT.rc"
sed -i "s#$m#<root>#g" "$OUT.output"
rm -f "$m/filler"
cp -a "$m" "$OUT"
)sh";
    const uint64_t size = (session_.empty() ? 0 : DirectoryBytes(session_)) +
                          (fs::exists(extra_) ? DirectoryBytes(extra_) : 0) + kPlentyBytes;
    const std::string env = "SIZE=" + std::to_string(size) + " SESSION='" + session_.string() +
                            "' EXTRA='" + extra_.string() + "' FREE=" + std::to_string(free_bytes) +
                            " OUT='" + out.string() + "' PROGRAM='" + program_ + "' ARGS='" + args +
                            "' PREPARE='" + prepare + "'";
    const CommandResult shell =
        RunCommand(env + " unshare --mount --propagation private bash " + script.string());
    FullDiskRun run;
    run.root = out;
    if (!fs::exists(out.string() + ".rc")) {
      run.result = {-1, "the small file system could not be set up: " + shell.output};
      return run;
    }
    run.result.exit_code = std::stoi(ReadBytes(out.string() + ".rc"));
    run.result.output = ReadBytes(out.string() + ".output");
    return run;
  }

 private:
  std::filesystem::path session_, extra_, work_;
  std::string program_;
  int runs_ = 0;
};

}  // namespace recon::testing
