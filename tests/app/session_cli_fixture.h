#pragma once

// What the session CLI tests share: running `recon`, reading its JSON, snapshotting a session's
// files, and a fixture giving each test its own folder.

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <nlohmann/json.hpp>
#include <regex>
#include <set>
#include <string>
#include <vector>

#include "tests/app/run_recon.h"

namespace recon::session_cli_testing {

namespace fs = std::filesystem;
using json = nlohmann::json;
using ::testing::HasSubstr;
using ::testing::Not;

using recon::testing::CommandResult;
using recon::testing::RunCommand;
using recon::testing::RunRecon;

// The unprivileged user the permission test runs `recon` as ("nobody").
constexpr int kNobody = 65534;

/// The JSON document a `--json` command printed (anything printed around it, such as a progress
/// line on stderr, is ignored): from the first line that starts with { or [.
inline json ParseJsonOutput(const CommandResult& result) {
  size_t begin = result.output.find_first_of("{[");
  while (begin != std::string::npos && begin > 0 && result.output[begin - 1] != '\n') {
    begin = result.output.find_first_of("{[", begin + 1);
  }
  const size_t end = result.output.find_last_of("}]");
  if (begin == std::string::npos || end == std::string::npos || end < begin) {
    ADD_FAILURE() << "no JSON in the output:\n" << result.output;
    return json::object();
  }
  try {
    return json::parse(result.output.substr(begin, end - begin + 1));
  } catch (const json::exception& e) {
    ADD_FAILURE() << "unparsable JSON (" << e.what() << "):\n" << result.output;
    return json::object();
  }
}

inline std::string ReadBytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

inline json ReadJson(const fs::path& path) {
  std::ifstream in(path);
  return json::parse(in);
}

inline void WriteJson(const fs::path& path, const json& value) {
  std::ofstream(path) << value.dump(2) << "\n";
}

/// The bytes of a session's manifest and episode files, by path relative to the session.
inline std::map<std::string, std::string> SnapshotSession(const fs::path& dir) {
  std::map<std::string, std::string> files;
  files["session.json"] = ReadBytes(dir / "session.json");
  for (const char* folder : {"episodes", "play", "trash"}) {
    if (!fs::is_directory(dir / folder)) continue;
    for (const fs::directory_entry& entry : fs::directory_iterator(dir / folder)) {
      files[fs::relative(entry.path(), dir).string()] = ReadBytes(entry.path());
    }
  }
  return files;
}

/// Episode names of `session episodes --json`, demonstrations only.
inline std::vector<std::string> DemoNames(const json& episodes) {
  std::vector<std::string> names;
  for (const json& e : episodes) {
    if (e.value("kind", "") == "demo") names.push_back(e["name"].get<std::string>());
  }
  return names;
}

inline std::vector<std::string> ExpectedDemoNames(int count) {
  std::vector<std::string> names;
  for (int i = 0; i < count; ++i) names.push_back("demo_" + std::to_string(i));
  return names;
}

inline const json* FindEpisode(const json& episodes, const std::string& name) {
  for (const json& e : episodes) {
    if (e.value("name", "") == name) return &e;
  }
  return nullptr;
}

/// Each test works in its own folder /tmp/session_cli_<test>_<pid> (mode 0755, so the
/// unprivileged user of the permission test can reach it), removed at the end.
class SessionCliTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const std::string test = ::testing::UnitTest::GetInstance()->current_test_info()->name();
    root_ = fs::path("/tmp") / ("session_cli_" + test + "_" + std::to_string(getpid()));
    fs::remove_all(root_);
    fs::create_directories(root_);
    fs::permissions(root_, fs::perms(0755));
  }

  void TearDown() override {
    std::error_code ignored;
    // A test may have made folders read-only; make them removable again.
    for (auto it = fs::recursive_directory_iterator(root_, ignored);
         it != fs::recursive_directory_iterator(); it.increment(ignored)) {
      if (it->is_directory(ignored)) fs::permissions(it->path(), fs::perms(0755), ignored);
    }
    fs::remove_all(root_, ignored);
  }

  fs::path Path(const std::string& name) const { return root_ / name; }

  static CommandResult Record(const fs::path& session, const std::string& args) {
    return RunRecon("record --session " + session.string() + " " + args);
  }

  static json Info(const fs::path& session) {
    const CommandResult r = RunRecon("session info " + session.string() + " --json");
    EXPECT_EQ(r.exit_code, 0) << r.output;
    return ParseJsonOutput(r);
  }

  static json Episodes(const fs::path& session) {
    const CommandResult r = RunRecon("session episodes " + session.string() + " --json");
    EXPECT_EQ(r.exit_code, 0) << r.output;
    return ParseJsonOutput(r);
  }

  fs::path root_;
};

}  // namespace recon::session_cli_testing
