// The studio's list of recent sessions offers only folders that still hold a session.

#include "app/studio/recent_sessions.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace recon::studio {
namespace {

namespace fs = std::filesystem;

TEST(RecentSessionsTest, OnlySessionsThatStillExistAreOffered) {
  const fs::path dir = fs::temp_directory_path() / ("recon-recent-" + std::to_string(getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir / "kept");
  fs::create_directories(dir / "emptied");
  std::ofstream(dir / "kept" / "session.json") << "{}";
  std::ofstream(dir / "emptied" / "session.json") << "{}";
  RecentSessions recent((dir / "recent.json").string());
  ASSERT_EQ(recent.Add((dir / "kept").string()), "");
  ASSERT_EQ(recent.Add((dir / "emptied").string()), "");
  ASSERT_EQ(recent.Add((dir / "gone").string()), "");  // never held one
  fs::remove(dir / "emptied" / "session.json");
  EXPECT_EQ(recent.entries().size(), 3u) << "the file keeps them all";
  EXPECT_EQ(recent.Openable(), std::vector<std::string>{(dir / "kept").string()});
  fs::remove_all(dir);
}

}  // namespace
}  // namespace recon::studio
