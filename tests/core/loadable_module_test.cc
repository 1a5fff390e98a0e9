// Loading a module on first use: what each way of failing says. (Loading the real modules is
// tested through the programs: CliTest.TorchIsLoadedOnlyByWhatNeedsIt,
// CameraCliTest.OpenCvIoIsLoadedOnlyByWhatNeedsIt.)

#include "engine/core/loadable_module.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdlib>
#include <string>

#include "engine/core/error.h"

namespace recon {
namespace {

using ::testing::HasSubstr;

std::string ErrorOf(const LoadableModule& module, int version) {
  try {
    LoadModuleTable(module, version);
  } catch (const UserError& e) {
    return e.what();
  }
  return "";
}

TEST(LoadableModuleTest, AMissingFileOrEntryIsAUserErrorNamingThePathAndWhatNeedsIt) {
  const std::string missing =
      ErrorOf({"/nonexistent/librecon_x.so", "ReconX", "the X module", "X needs it"}, 1);
  EXPECT_THAT(missing, HasSubstr("cannot load the X module /nonexistent/librecon_x.so ("));
  EXPECT_THAT(missing, HasSubstr("): X needs it; ./scripts/build builds it"));
  // A library that loads but is not a module of ours.
  const std::string no_entry = ErrorOf({"libm.so.6", "ReconX", "the X module", "X needs it"}, 1);
  EXPECT_THAT(no_entry, HasSubstr("the X module libm.so.6 has no ReconX: X needs it"));
}

TEST(LoadableModuleTest, TheEnvironmentNamesAnotherCopy) {
  ::setenv("RECON_TEST_MODULE_PATH", "/elsewhere/librecon_x.so", 1);
  EXPECT_EQ(ModulePath("RECON_TEST_MODULE_PATH", "/built/librecon_x.so"),
            "/elsewhere/librecon_x.so");
  ::setenv("RECON_TEST_MODULE_PATH", "", 1);
  EXPECT_EQ(ModulePath("RECON_TEST_MODULE_PATH", "/built/librecon_x.so"), "/built/librecon_x.so");
  ::unsetenv("RECON_TEST_MODULE_PATH");
  EXPECT_EQ(ModulePath("RECON_TEST_MODULE_PATH", "/built/librecon_x.so"), "/built/librecon_x.so");
}

}  // namespace
}  // namespace recon
