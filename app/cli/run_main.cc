#include "app/cli/run_main.h"

#include <cstdio>
#include <exception>
#include <filesystem>
#include <string>

#include "app/cli/crash_report.h"
#include "engine/core/error.h"

namespace recon::cli {

namespace {

std::vector<std::string>& Arguments() {
  static std::vector<std::string> arguments;
  return arguments;
}

}  // namespace

const std::vector<std::string>& CommandLine() { return Arguments(); }

int RunMain(CLI::App& app, int argc, char** argv, const char* program,
            const std::function<void()>& run) {
  InstallCrashReport(program);
  Arguments().assign(argv + (argc > 0 ? 1 : 0), argv + argc);
  try {
    app.parse(argc, argv);
    if (run) run();
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    // CLI11 uses 0 for --help/--version; every real parse error is a usage error (2).
    return code == 0 ? 0 : 2;
  } catch (const UserError& e) {
    std::fprintf(stderr, "\n%s: error: %s\n", program, e.what());
    return 2;
  } catch (const DivergenceError& e) {
    // A learning rate (or data) the training could not follow: the message says which step and
    // what to try; nothing was saved from the run that diverged.
    std::fprintf(stderr, "\n%s: error: %s\n", program, e.what());
    return 2;
  } catch (const std::filesystem::filesystem_error& e) {
    // The file system refused a path (a link loop, a name too long, a folder where a file
    // should be): a fault of what is on disk, said with the path, not a defect of the program.
    std::string paths = e.path1().string();
    if (!e.path2().empty()) paths += " -> " + e.path2().string();
    std::fprintf(stderr, "\n%s: error: %s: %s\n", program, paths.c_str(),
                 e.code().message().c_str());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "\n%s: internal error: %s\n", program, e.what());
    return 1;
  }
  return 0;
}

}  // namespace recon::cli
