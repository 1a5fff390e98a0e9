#pragma once

// What the fault tests of the real binaries check of the files a command leaves: a snapshot of
// a folder, and whether a file is complete of its kind (shared by DiskFullTest and
// FaultInjectionTest).

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <string>

#include "engine/learn/learner.h"
#include "engine/store/h5.h"

namespace recon::testing {

namespace fs = std::filesystem;

inline std::string ReadBytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

/// Every regular file under `dir`, by relative path, with its bytes.
inline std::map<std::string, std::string> Snapshot(const fs::path& dir) {
  std::map<std::string, std::string> files;
  if (!fs::exists(dir)) return files;
  for (const auto& entry : fs::recursive_directory_iterator(dir)) {
    if (entry.is_regular_file()) {
      files[fs::relative(entry.path(), dir).string()] = ReadBytes(entry.path());
    }
  }
  return files;
}

inline uint64_t DirectoryBytes(const fs::path& dir) {
  uint64_t total = 0;
  for (const auto& entry : fs::recursive_directory_iterator(dir)) {
    if (entry.is_regular_file()) total += entry.file_size();
  }
  return total;
}

inline bool EndsWith(const std::string& text, const std::string& tail) {
  return text.size() >= tail.size() &&
         text.compare(text.size() - tail.size(), tail.size(), tail) == 0;
}

/// Why `path` is not a complete file of its kind, or "" when it is.
inline std::string Incomplete(const fs::path& path) {
  const std::string name = path.filename().string();
  const std::string ext = path.extension().string();
  try {
    if (ext == ".h5" || ext == ".hdf5") {
      store::h5::File file = store::h5::File::OpenReadOnly(path.string());
      store::h5::VerifyChecksums(file, file.id(), {});
      file.Close();
    } else if (ext == ".ckpt") {
      (void)learn::LoadPolicy(path.string());
    } else if (ext == ".json") {
      const nlohmann::json parsed = nlohmann::json::parse(ReadBytes(path));
      if (parsed.is_discarded()) return "unparsable JSON";
    } else if (ext == ".png") {
      // A PNG ends with its IEND chunk (the name and its CRC).
      const std::string bytes = ReadBytes(path);
      if (!EndsWith(bytes, std::string("IEND\xae\x42\x60\x82", 8))) return "a PNG cut short";
    } else if (ext == ".html") {
      if (!EndsWith(ReadBytes(path), "</html>\n")) return "a page cut short";
    } else if (ext == ".svg") {
      if (!EndsWith(ReadBytes(path), "</svg>\n")) return "a drawing cut short";
    } else if (ext == ".csv") {
      // Every row as many fields as the header, and the last row ended.
      const std::string text = ReadBytes(path);
      if (text.empty() || text.back() != '\n') return "a table cut short";
      size_t header_fields = 0;
      size_t line_start = 0;
      while (line_start < text.size()) {
        const size_t line_end = text.find('\n', line_start);
        const std::string line = text.substr(line_start, line_end - line_start);
        const size_t fields = 1 + static_cast<size_t>(std::count(line.begin(), line.end(), ','));
        if (header_fields == 0) header_fields = fields;
        if (fields != header_fields) return "a row with " + std::to_string(fields) + " fields";
        line_start = line_end + 1;
      }
    } else if (name == ".lock") {
      return "";
    } else {
      return "a file of a kind this test does not know (" + name + ")";
    }
  } catch (const std::exception& e) {
    return e.what();
  }
  return "";
}

}  // namespace recon::testing
