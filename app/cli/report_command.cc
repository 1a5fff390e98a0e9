#include "app/cli/report_command.h"

#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>

#include "app/cli/output_path.h"
#include "app/cli/session_report_builder.h"
#include "engine/store/session.h"

namespace recon::cli {

namespace {

namespace fs = std::filesystem;

struct ReportFlags {
  std::string dir;
  std::string out;
  std::string episode;
  bool force = false;
};

void RunReport(const ReportFlags& flags) {
  const store::Session session = store::Session::Open(flags.dir, store::Session::Access::kReadOnly);
  if (!flags.out.empty()) {
    CheckOutputFolder("--out", flags.out, flags.force, "report.html",
                      (fs::path(flags.dir) / "report").string());
  }
  const std::string html = WriteReportForSession(session, flags.out, flags.episode);
  const fs::path figures = fs::path(html).parent_path() / "figures";
  int count = 0;
  for (const auto& entry : fs::directory_iterator(figures))
    count += entry.path().extension() == ".png";
  std::printf("wrote %s (%d figures as PNG in %s)\n", html.c_str(), count, figures.c_str());
}

}  // namespace

void AddReportCommand(CLI::App& app) {
  auto flags = std::make_shared<ReportFlags>();
  CLI::App* command =
      app.add_subcommand("report", "write a session's self-contained HTML report with its figures");
  command->add_option("dir", flags->dir, "session folder")->required();
  command->add_option("--out", flags->out, "report folder (default: DIR/report)");
  command->add_flag("--force", flags->force, "write into a folder that holds other files");
  command->add_option("--episode", flags->episode,
                      "episode whose beacon traces are drawn (default: the first good one)");
  command->callback([flags] { RunReport(*flags); });
}

}  // namespace recon::cli
