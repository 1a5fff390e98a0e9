#include "engine/core/files.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>

#include "engine/core/error.h"

namespace recon {

namespace fs = std::filesystem;

std::optional<FileStamp> StampOf(const std::string& path) {
  struct stat info {};
  if (::stat(path.c_str(), &info) != 0) return std::nullopt;
  return FileStamp{static_cast<uint64_t>(info.st_ino),
                   static_cast<int64_t>(info.st_mtim.tv_sec) * 1000000000 + info.st_mtim.tv_nsec};
}

namespace {

// What a file system entry that is not a regular file is, in a user's words.
std::string KindOfEntry(mode_t mode) {
  if (S_ISDIR(mode)) return "a folder";
  if (S_ISFIFO(mode)) return "a named pipe (FIFO)";
  if (S_ISCHR(mode) || S_ISBLK(mode)) return "a device";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a regular file";
}

[[noreturn]] void FailNotAFile(const std::string& path, mode_t mode) {
  throw UserError(path + ": is " + KindOfEntry(mode) + ", not a file");
}

std::string Mebibytes(int64_t bytes) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.0f MiB", static_cast<double>(bytes) / (1 << 20));
  return text;
}

}  // namespace

void RefuseNonRegularFile(const std::string& path) {
  struct stat info {};
  if (::stat(path.c_str(), &info) != 0) return;
  if (!S_ISREG(info.st_mode)) FailNotAFile(path, info.st_mode);
}

std::optional<std::string> ReadWholeFile(const std::string& path, int64_t max_bytes) {
  // Non-blocking, so that a named pipe opens at once and is refused below instead of waiting.
  const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) return std::nullopt;
  struct Closer {
    int fd;
    ~Closer() { ::close(fd); }
  } closer{fd};
  struct stat info {};
  if (::fstat(fd, &info) != 0) return std::nullopt;
  if (!S_ISREG(info.st_mode)) FailNotAFile(path, info.st_mode);
  const auto too_big = [&] {
    throw UserError(path + ": is over " + Mebibytes(max_bytes) +
                    ", more than a file read whole may be");
  };
  if (info.st_size > max_bytes) too_big();
  std::string content;
  content.reserve(static_cast<size_t>(info.st_size));
  char buffer[1 << 16];
  for (;;) {
    const ssize_t n = ::read(fd, buffer, sizeof(buffer));
    if (n == 0) break;
    if (n < 0) {
      if (errno == EINTR) continue;
      return std::nullopt;
    }
    // A file that grows while it is read (or a /proc file, whose size says 0) is bounded too.
    if (static_cast<int64_t>(content.size()) + n > max_bytes) too_big();
    content.append(buffer, static_cast<size_t>(n));
  }
  return content;
}

std::string TemporarySibling(const std::string& path) {
  return path + ".tmp." + std::to_string(getpid());
}

std::string NameTheTarget(std::string message, const std::string& tmp, const std::string& target) {
  if (tmp.empty()) return message;
  for (size_t at = message.find(tmp); at != std::string::npos;
       at = message.find(tmp, at + target.size())) {
    message.replace(at, tmp.size(), target);
  }
  return message;
}

bool IsTemporaryOfDeadWriter(const std::string& file_name, const std::string& marker) {
  const size_t at = file_name.rfind(marker);
  if (at == std::string::npos) return false;
  const std::string digits = file_name.substr(at + marker.size());
  if (digits.empty() || digits.size() > 9 ||
      digits.find_first_not_of("0123456789") != std::string::npos) {
    return false;
  }
  const pid_t pid = static_cast<pid_t>(std::stol(digits));
  return pid > 0 && ::kill(pid, 0) != 0 && errno == ESRCH;
}

int RemoveDeadTemporariesIn(const std::string& folder, const std::string& prefix) {
  int removed = 0;
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator(folder, ec)) {
    const std::string name = entry.path().filename().string();
    if (name.rfind(prefix, 0) != 0 || !IsTemporaryOfDeadWriter(name)) continue;
    if (std::filesystem::remove(entry.path(), ec)) ++removed;
  }
  return removed;
}

int RemoveDeadStagingFoldersOf(const std::string& path, const std::string& marker) {
  const std::filesystem::path target(path);
  const std::string prefix = target.filename().string() + marker;
  const std::filesystem::path folder = target.parent_path().empty() ? "." : target.parent_path();
  int removed = 0;
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator(folder, ec)) {
    const std::string name = entry.path().filename().string();
    if (name.rfind(prefix, 0) != 0 || !IsTemporaryOfDeadWriter(name, marker)) continue;
    if (std::filesystem::remove_all(entry.path(), ec) > 0) ++removed;
  }
  return removed;
}

int RemoveDeadTemporariesOf(const std::string& path) {
  const std::filesystem::path target(path);
  return RemoveDeadTemporariesIn(target.parent_path().empty() ? "." : target.parent_path().string(),
                                 target.filename().string() + ".tmp.");
}

void ReplaceFile(const std::string& from, const std::string& to) {
  if (std::rename(from.c_str(), to.c_str()) != 0) {
    const std::string reason = std::strerror(errno);
    std::remove(from.c_str());
    throw UserError("cannot write " + to + ": " + reason);
  }
}

void WriteWholeFile(const std::string& path, const std::string& content) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) throw UserError("cannot write " + path + ": " + std::strerror(errno));
  auto fail = [&](bool close_it) {
    const std::string reason = std::strerror(errno);
    if (close_it) ::close(fd);
    std::remove(path.c_str());
    throw UserError("cannot write " + path + ": " + reason);
  };
  size_t written = 0;
  while (written < content.size()) {
    const ssize_t n = ::write(fd, content.data() + written, content.size() - written);
    if (n < 0) {
      if (errno == EINTR) continue;
      fail(true);
    }
    written += static_cast<size_t>(n);
  }
  if (::close(fd) != 0) fail(false);
}

void WriteFileAtomically(const std::string& path, const std::string& content) {
  RemoveDeadTemporariesOf(path);
  const std::string tmp = TemporarySibling(path);
  try {
    WriteWholeFile(tmp, content);
    // fsync so that after a power loss the rename never points at an empty file.
    SyncFile(tmp);
  } catch (const UserError& e) {
    std::remove(tmp.c_str());
    throw UserError(NameTheTarget(e.what(), tmp, path));
  }
  ReplaceFile(tmp, path);
}

void SyncFile(const std::string& path) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) throw UserError("cannot open " + path + ": " + std::strerror(errno));
  const int result = ::fsync(fd);
  const int saved_errno = errno;
  ::close(fd);
  if (result != 0) throw UserError("cannot flush " + path + ": " + std::strerror(saved_errno));
}

void SyncDirectory(const std::string& dir) {
  const int fd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) return;
  ::fsync(fd);
  ::close(fd);
}

void EnsureWritableDirectory(const std::string& dir) {
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw UserError("cannot create output folder " + dir + ": " + ec.message());
  if (!fs::is_directory(dir)) throw UserError("output path " + dir + " is not a folder");
  // One name per call: threads of one process (methods training side by side) probe the same
  // folder at once, and O_EXCL would fail the second with "File exists".
  static std::atomic<uint64_t> probes{0};
  const std::string probe = (fs::path(dir) / (".write-test." + std::to_string(getpid()) + "." +
                                              std::to_string(probes.fetch_add(1))))
                                .string();
  const int fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
  if (fd < 0) {
    throw UserError("output folder " + dir + " is not writable: " + std::strerror(errno));
  }
  ::close(fd);
  std::remove(probe.c_str());
}

}  // namespace recon
