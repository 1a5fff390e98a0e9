// The CLI's progress line as a log sees it (not a terminal): what it prints and how often.

#include "engine/core/progress.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <sstream>
#include <string>
#include <vector>

namespace recon {
namespace {

// Everything `use` makes a ProgressLine print into a file (a file is not a terminal), as lines.
template <typename Use>
std::vector<std::string> LinesPrinted(Use use) {
  std::FILE* file = std::tmpfile();
  EXPECT_NE(file, nullptr);
  use(file);
  std::rewind(file);
  std::string text;
  char buffer[256];
  size_t n = 0;
  while ((n = std::fread(buffer, 1, sizeof(buffer), file)) > 0) text.append(buffer, n);
  std::fclose(file);
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

TEST(ProgressLineTest, TheEndIsPrintedOnceHoweverOftenItIsReported) {
  const std::vector<std::string> lines = LinesPrinted([](std::FILE* out) {
    ProgressLine progress("training", 10, out);
    progress.Advance(10, "both 5");
    // A job that keeps reporting at the end (a restarted training run) adds nothing.
    for (int i = 0; i < 5; ++i) progress.Advance(0, "both 5");
    progress.Finish();
  });
  ASSERT_EQ(lines.size(), 1u);
  EXPECT_NE(lines[0].find("training [##############################] 10/10 100%"),
            std::string::npos)
      << lines[0];
  EXPECT_NE(lines[0].find("both 5"), std::string::npos) << lines[0];
}

TEST(ProgressLineTest, ALogGetsAtMostTheStartedLinesAndTheEnd) {
  const std::vector<std::string> lines = LinesPrinted([](std::FILE* out) {
    ProgressLine progress("steps", 1000, out);
    for (int i = 0; i < 999; ++i) progress.Advance(1);  // far quicker than the 5 s between lines
    progress.Finish();
  });
  ASSERT_EQ(lines.size(), 1u);  // only the final state: the work never ran 5 s
  EXPECT_NE(lines[0].find("999/1000"), std::string::npos) << lines[0];
}

}  // namespace
}  // namespace recon
