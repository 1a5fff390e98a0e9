#include "devices/render/egl_context.h"

#include <GL/gl.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>
#include <thread>

#include "devices/render/mujoco_renderer.h"
#include "engine/core/error.h"
#include "engine/worlds/mujoco_model.h"
#include "tests/render/test_scene.h"

namespace recon::render {
namespace {

using ::testing::HasSubstr;

std::string GlVersion() {
  const auto* text = reinterpret_cast<const char*>(glGetString(GL_VERSION));
  return text != nullptr ? text : "(no current context)";
}

TEST(EglContextTest, IsADesktopCompatibilityProfileContextCurrentOnThisThread) {
  EglContext context;
  EXPECT_TRUE(context.IsCurrent());
  // MuJoCo 2.2 needs fixed-function OpenGL: a core profile would break it.
  EXPECT_THAT(GlVersion(), HasSubstr("Compatibility Profile"));
  EXPECT_THAT(context.description(), HasSubstr("EGL"));
  EXPECT_THAT(context.description(), HasSubstr("Compatibility Profile"));
}

TEST(EglContextTest, ASecondContextLeavesTheFirstCurrentAndScopedCurrentRestoresIt) {
  EglContext first;
  ASSERT_TRUE(first.IsCurrent());
  EglContext second;
  EXPECT_TRUE(first.IsCurrent());
  EXPECT_FALSE(second.IsCurrent());
  {
    ScopedCurrent current(second);
    EXPECT_TRUE(second.IsCurrent());
    EXPECT_THAT(GlVersion(), HasSubstr("Compatibility Profile"));
  }
  EXPECT_TRUE(first.IsCurrent());
  second.MakeCurrent();
  EXPECT_TRUE(second.IsCurrent());
  first.MakeCurrent();
  EXPECT_TRUE(first.IsCurrent());
}

TEST(EglContextTest, AContextCurrentOnAnotherThreadIsAUserErrorWithTheEglCode) {
  EglContext context;
  ASSERT_TRUE(context.IsCurrent());
  std::string message = "no UserError";
  std::thread other([&] {
    try {
      context.MakeCurrent();
    } catch (const UserError& e) {
      message = e.what();
    }
  });
  other.join();
  EXPECT_THAT(message, HasSubstr("eglMakeCurrent failed: EGL_BAD_ACCESS (0x3002)"));
}

TEST(EglContextTest, RendererLeavesTheCallersContextCurrent) {
  // The UI thread's context must survive a simulated camera rendering on the same thread.
  EglContext ui;
  worlds::MujocoModel scene =
      worlds::MujocoModel::FromString(testing::kTestScene, "render test scene");
  MujocoRenderer renderer;
  EXPECT_TRUE(ui.IsCurrent());
  renderer.Render(scene, "top", 32, 32);
  EXPECT_TRUE(ui.IsCurrent());
}

TEST(EglContextTest, DestroyingOneContextDoesNotBreakAnotherOnTheSameDisplay) {
  // Every context shares the process's one surfaceless EGLDisplay. Terminating it when one
  // renderer goes away marks the others' contexts for deletion, which happens as soon as they
  // stop being current: the survivor would then fail on its next eglMakeCurrent.
  worlds::MujocoModel scene =
      worlds::MujocoModel::FromString(testing::kTestScene, "render test scene");
  mj_forward(scene.model(), scene.data());
  MujocoRenderer survivor;
  const RgbImage before = survivor.Render(scene, "top", 64, 64);
  std::exception_ptr error;
  std::thread([&] {
    try {
      worlds::MujocoModel own_scene =
          worlds::MujocoModel::FromString(testing::kTestScene, "render test scene");
      MujocoRenderer short_lived;
      short_lived.Render(own_scene, "top", 64, 64);
    } catch (...) {
      error = std::current_exception();
    }
  }).join();
  if (error) std::rethrow_exception(error);
  {
    // Take the survivor's context off this thread, so that its next frame must re-bind it.
    EglContext other;
    other.MakeCurrent();
  }
  EXPECT_EQ(survivor.Render(scene, "top", 64, 64).rgb, before.rgb);
  EXPECT_GT(testing::FindBlob(before, testing::IsRed).count, 30);
}

TEST(EglContextDeathTest, WithoutAMesaDriverTheErrorNamesEachFailedCallAndItsCode) {
  // The check runs in a fresh child process ("threadsafe" style re-executes this binary), so that
  // Mesa is not loaded yet when it is pointed at a directory without drivers.
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  EXPECT_EXIT(
      {
        setenv("LIBGL_DRIVERS_PATH", "/nonexistent", 1);
        std::string why;
        const bool available = HeadlessRenderingAvailable(&why);
        std::fprintf(stderr, "why: %s\n", why.c_str());
        std::exit(available ? 1 : 0);
      },
      ::testing::ExitedWithCode(0),
      "why: cannot create a headless OpenGL context: eglInitialize\\(surfaceless display\\) "
      "failed: EGL_NOT_INITIALIZED \\(0x3001\\)");
}

}  // namespace
}  // namespace recon::render
