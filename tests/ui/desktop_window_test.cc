// The studio in a real desktop window, on a virtual X server (Xvfb) each test starts for itself:
// the real recon-studio binary is clicked through xdotool (XTEST input, as from a mouse), and a
// DesktopWindow in this process gets typed text, held keys, a resize and a close request. Xvfb
// and xdotool come from scripts/install-deps; without them these tests fail, they never skip.

#include "ui/platform/desktop_window.h"

#include <fcntl.h>
#include <gtest/gtest.h>
#include <imgui.h>
#include <poll.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <future>
#include <optional>
#include <sstream>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "engine/core/error.h"
#include "tests/support/golden_image.h"
#include "tests/support/run_command.h"

// Last: Xlib defines macros (None, Bool, Status, Success) that other headers use as names.
#include <X11/Xatom.h>
#include <X11/Xlib.h>
#include <X11/Xutil.h>

namespace recon::ui {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

/// Deadlines only end a test that hangs; no test asserts on how long anything takes.
constexpr auto kDeadline = std::chrono::seconds(30);

std::string ReadFile(const fs::path& path) {
  std::ifstream in(path);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

/// Whether `program` is on the PATH.
bool Installed(const std::string& program) {
  return testing::RunCommand("command -v " + program + " >/dev/null").exit_code == 0;
}

/// A virtual X server for one test, on a display number it picks itself (-displayfd: Xvfb
/// writes the number once it accepts connections, so parallel tests never collide), and this
/// process's own connection to it. Stopped and waited for on destruction.
class VirtualDisplay {
 public:
  VirtualDisplay() {
    for (const char* program : {"Xvfb", "xdotool"}) {
      if (!Installed(program)) {
        error_ = std::string(program) + " is not installed: run scripts/install-deps";
        return;
      }
    }
    log_ = fs::temp_directory_path() / ("recon-xvfb-" + std::to_string(getpid()) + ".log");
    int ready[2];
    if (pipe(ready) != 0) {
      error_ = "pipe failed";
      return;
    }
    const std::string fd = std::to_string(ready[1]);
    const char* argv[] = {"Xvfb",         "-displayfd", fd.c_str(), "-screen", "0",
                          "1280x1024x24", "-nolisten",  "tcp",      nullptr};
    const int log = open(log_.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    pid_ = fork();
    if (pid_ == 0) {
      // The server dies with this process, even when a crash or ctest's timeout ends it before
      // the destructor runs. Only async-signal-safe calls until exec.
      prctl(PR_SET_PDEATHSIG, SIGTERM);
      close(ready[0]);
      dup2(log, 1);
      dup2(log, 2);
      execvp("Xvfb", const_cast<char**>(argv));
      _exit(127);
    }
    close(log);
    close(ready[1]);
    if (pid_ < 0) {
      close(ready[0]);
      error_ = "fork failed";
      return;
    }
    std::string number;
    const auto deadline = Clock::now() + kDeadline;
    for (char c = 0; c != '\n' && Clock::now() < deadline;) {
      pollfd p{ready[0], POLLIN, 0};
      if (poll(&p, 1, 200) <= 0) continue;
      if (read(ready[0], &c, 1) != 1) break;  // Xvfb exited
      if (c != '\n') number += c;
    }
    close(ready[0]);
    if (number.empty()) {
      error_ = "Xvfb did not start: " + ReadFile(log_);
      return;
    }
    name_ = ":" + number;
    // Xlib's default handler exits the process on a protocol error, e.g. grabbing a window that
    // has just been closed.
    XSetErrorHandler([](Display*, XErrorEvent*) { return 0; });
    x_ = XOpenDisplay(name_.c_str());
    if (x_ == nullptr) error_ = "Xvfb started on " + name_ + " but refuses connections";
  }

  ~VirtualDisplay() {
    if (x_ != nullptr) XCloseDisplay(x_);  // before the server goes
    if (pid_ > 0) {
      kill(pid_, SIGTERM);
      waitpid(pid_, nullptr, 0);
    }
    if (!log_.empty()) fs::remove(log_);
  }

  /// Empty once the server accepts connections; otherwise what went wrong.
  const std::string& error() const { return error_; }
  /// The DISPLAY value, e.g. ":3".
  const std::string& name() const { return name_; }

  /// A command line run with DISPLAY set to this server, stderr joined to stdout.
  testing::CommandResult Run(const std::string& command) const {
    return testing::RunCommand("DISPLAY=" + name_ + " " + command);
  }

  /// Sets the server's resource database (what xrdb would load), e.g. "Xft.dpi:\t192\n": where
  /// desktops keep the screen's DPI setting, which clients read as their content scale.
  void SetResources(const std::string& resources) const {
    XChangeProperty(x_, DefaultRootWindow(x_), XA_RESOURCE_MANAGER, XA_STRING, 8, PropModeReplace,
                    reinterpret_cast<const unsigned char*>(resources.data()),
                    static_cast<int>(resources.size()));
    XSync(x_, False);
  }

  /// The X window whose title matches `title` (an xdotool regular expression), once it is
  /// visible; 0 if none appears before the deadline.
  unsigned long FindWindow(const std::string& title) const {
    const testing::CommandResult r =
        Run("timeout 30 xdotool search --sync --onlyvisible --name '" + title + "'");
    return r.exit_code == 0 ? std::strtoul(r.output.c_str(), nullptr, 10) : 0;
  }

  /// What the X server shows of `window` (empty if it is gone).
  RgbImage Grab(unsigned long window) const {
    XWindowAttributes attributes;
    if (XGetWindowAttributes(x_, window, &attributes) == 0) return {};
    XImage* image =
        XGetImage(x_, window, 0, 0, attributes.width, attributes.height, AllPlanes, ZPixmap);
    if (image == nullptr) return {};
    const auto channel = [](unsigned long pixel, unsigned long mask) {
      int shift = 0;
      while (mask != 0 && (mask & 1) == 0) mask >>= 1, ++shift;
      return static_cast<uint8_t>((pixel >> shift) & 0xff);
    };
    RgbImage rgb;
    rgb.width = image->width;
    rgb.height = image->height;
    rgb.rgb.reserve(static_cast<size_t>(rgb.width) * rgb.height * 3);
    for (int y = 0; y < rgb.height; ++y) {
      for (int x = 0; x < rgb.width; ++x) {
        const unsigned long pixel = XGetPixel(image, x, y);
        rgb.rgb.push_back(channel(pixel, image->red_mask));
        rgb.rgb.push_back(channel(pixel, image->green_mask));
        rgb.rgb.push_back(channel(pixel, image->blue_mask));
      }
    }
    XDestroyImage(image);
    return rgb;
  }

  /// The smallest size `window` asks its window manager to allow (WM_NORMAL_HINTS); {0, 0}
  /// when it asks for none.
  std::pair<int, int> MinimumSize(unsigned long window) const {
    XSizeHints hints{};
    long supplied = 0;
    if (XGetWMNormalHints(x_, window, &hints, &supplied) == 0 || !(hints.flags & PMinSize)) {
      return {0, 0};
    }
    return {hints.min_width, hints.min_height};
  }

  /// Asks `window` to close as a window manager's close button does (WM_DELETE_WINDOW).
  void RequestClose(unsigned long window) const {
    XEvent event{};
    event.xclient.type = ClientMessage;
    event.xclient.window = window;
    event.xclient.message_type = XInternAtom(x_, "WM_PROTOCOLS", False);
    event.xclient.format = 32;
    event.xclient.data.l[0] = static_cast<long>(XInternAtom(x_, "WM_DELETE_WINDOW", False));
    event.xclient.data.l[1] = CurrentTime;
    XSendEvent(x_, window, False, NoEventMask, &event);
    XFlush(x_);
  }

 private:
  std::string error_;
  std::string name_;
  fs::path log_;
  pid_t pid_ = -1;
  Display* x_ = nullptr;
};

/// A rectangle of pixels, in the coordinates of the golden image it was cut from.
struct Rect {
  int x, y, width, height;
};

RgbImage Crop(const RgbImage& image, int x0, int y0, int width, int height) {
  RgbImage out;
  if (x0 < 0 || y0 < 0 || x0 + width > image.width || y0 + height > image.height) return out;
  out.width = width;
  out.height = height;
  for (int y = y0; y < y0 + height; ++y) {
    const uint8_t* row = image.Pixel(y, x0);
    out.rgb.insert(out.rgb.end(), row, row + static_cast<size_t>(width) * 3);
  }
  return out;
}

/// Whether `image` shows `golden`'s `rect` moved down by `dy` pixels, within the golden
/// comparison's own tolerances.
::testing::AssertionResult ShowsGoldenPart(const RgbImage& image, const RgbImage& golden, Rect rect,
                                           int dy) {
  const RgbImage want = Crop(golden, rect.x, rect.y, rect.width, rect.height);
  const RgbImage got = Crop(image, rect.x, rect.y + dy, rect.width, rect.height);
  if (got.width == 0) return ::testing::AssertionFailure() << "the region is outside the image";
  const testing::GoldenOptions tolerance;
  const testing::ImageDifference d =
      testing::CompareImages(want, got, tolerance.per_channel_tolerance);
  if (d.fraction_over_tolerance <= tolerance.max_fraction_over_tolerance) {
    return ::testing::AssertionSuccess();
  }
  return ::testing::AssertionFailure()
         << d.fraction_over_tolerance * 100 << " % of the pixels of golden region (" << rect.x
         << ", " << rect.y << ", " << rect.width << "x" << rect.height << ") differ, shifted by "
         << dy << " px (largest channel difference " << d.max_channel_difference << ")";
}

/// How far down `image` shows `golden`'s `rect` (0 first, then up to 40 pixels either way; the
/// goldens match the studio, but a shift should not hide that the rest works), if it does.
std::optional<int> FindGoldenPart(const RgbImage& image, const RgbImage& golden, Rect rect) {
  for (int shift = 0; shift <= 40; ++shift) {
    for (const int dy : {shift, -shift}) {
      if (ShowsGoldenPart(image, golden, rect, dy)) return dy;
    }
  }
  return std::nullopt;
}

/// The bands of rows, [first, end), in which `a` and `b` differ within columns [x0, x1).
std::vector<std::pair<int, int>> DifferingRows(const RgbImage& a, const RgbImage& b, int x0,
                                               int x1) {
  std::vector<std::pair<int, int>> bands;
  for (int y = 0; y < std::min(a.height, b.height); ++y) {
    bool differs = false;
    for (int x = x0; x < x1 && !differs; ++x)
      differs = std::memcmp(a.Pixel(y, x), b.Pixel(y, x), 3);
    if (!differs) continue;
    if (!bands.empty() && bands.back().second == y) {
      bands.back().second = y + 1;
    } else {
      bands.push_back({y, y + 1});
    }
  }
  return bands;
}

RgbImage Golden(const std::string& name) {
  return testing::ReadPng(std::string(RECON_SOURCE_DIR) + "/assets/goldens/" + name + ".png");
}

/// Where the studio_cell and studio_beacons goldens differ, found in the goldens themselves so
/// that the test follows their layout: in the step list only the selection moves from the Cell
/// row to the Beacons row; the step's screen starts with its heading.
struct BeaconsRegions {
  Rect beacons_row;  ///< the Beacons row's title line (enabled in one, selected in the other)
  Rect both_rows;    ///< from the Cell row's title line to the Beacons row's
  Rect heading;      ///< the screen's heading
};

::testing::AssertionResult FindBeaconsRegions(const RgbImage& cell, const RgbImage& beacons,
                                              BeaconsRegions& regions) {
  // Columns well inside the step list (the screens start to its right, past x = 270).
  constexpr int kListWidth = 200;
  const std::vector<std::pair<int, int>> rows = DifferingRows(cell, beacons, 0, kListWidth);
  if (rows.size() != 2) {
    return ::testing::AssertionFailure()
           << "the goldens' step lists differ in " << rows.size()
           << " bands, not in the two rows whose selection moves; update this test";
  }
  const std::vector<std::pair<int, int>> screen = DifferingRows(cell, beacons, 300, 1000);
  if (screen.empty()) return ::testing::AssertionFailure() << "the goldens' screens are the same";
  regions.beacons_row = {0, rows[1].first, kListWidth, rows[1].second - rows[1].first};
  regions.both_rows = {0, rows[0].first, kListWidth, rows[1].second - rows[0].first};
  regions.heading = {276, screen[0].first, 600, 20};
  return ::testing::AssertionSuccess();
}

TEST(StudioWindowTest, AClickInTheWindowOpensBeaconsAndTheLastFrameIsWrittenOnClose) {
  const fs::path dir = fs::temp_directory_path() / ("recon-window-" + std::to_string(getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  const RgbImage cell_golden = Golden("studio_cell");
  const RgbImage beacons_golden = Golden("studio_beacons");
  BeaconsRegions regions;
  ASSERT_TRUE(FindBeaconsRegions(cell_golden, beacons_golden, regions));
  // Declared before the display: if the test stops early, the server goes first and takes the
  // studio with it, so waiting for the studio cannot hang.
  std::future<testing::CommandResult> studio;
  VirtualDisplay display;
  ASSERT_EQ(display.error(), "");
  // No --frames: the studio runs until its window is closed. `timeout` is a last resort only.
  // Its list of recent sessions under the test's folder, never the user's own.
  const std::string command =
      "DISPLAY=" + display.name() + " XDG_CONFIG_HOME=" + (dir / "config").string() +
      " timeout -s KILL 120 " + RECON_STUDIO + " --session " + (dir / "session").string() +
      " --width 1280 --height 800 --screenshot " + (dir / "last.png").string();
  studio = std::async(std::launch::async, [command] { return testing::RunCommand(command); });
  const unsigned long window = display.FindWindow("^RECON Studio - ");
  ASSERT_NE(window, 0u) << "no studio window appeared";

  // Click only once the step list shows Beacons enabled (the cell is up).
  std::optional<int> dy;
  for (const auto deadline = Clock::now() + kDeadline; !dy && Clock::now() < deadline;) {
    dy = FindGoldenPart(display.Grab(window), cell_golden, regions.beacons_row);
    if (!dy) std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  ASSERT_TRUE(dy.has_value()) << "the window never showed an enabled 'Beacons' step";
  const int x = 40;  // on the title
  const int y = regions.beacons_row.y + *dy + regions.beacons_row.height / 2;
  testing::CommandResult click =
      display.Run("xdotool mousemove --window " + std::to_string(window) + " " + std::to_string(x) +
                  " " + std::to_string(y) + " click 1");
  ASSERT_EQ(click.exit_code, 0) << click.output;
  // Away from the row again: a hovered row is drawn in another shade than in the golden.
  click = display.Run("xdotool mousemove --window " + std::to_string(window) + " 1100 700");
  ASSERT_EQ(click.exit_code, 0) << click.output;
  bool shown = false;
  for (const auto deadline = Clock::now() + kDeadline; !shown && Clock::now() < deadline;) {
    shown = ShowsGoldenPart(display.Grab(window), beacons_golden, regions.both_rows, *dy);
    if (!shown) std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  display.RequestClose(window);
  ASSERT_EQ(studio.wait_for(kDeadline), std::future_status::ready) << "closing did not end it";
  const testing::CommandResult result = studio.get();
  ASSERT_EQ(result.exit_code, 0) << result.output;
  EXPECT_NE(result.output.find("recon-studio: window on display " + display.name() + " ("),
            std::string::npos)
      << result.output;
  EXPECT_TRUE(shown) << "the window never showed the Beacons step selected";

  // The frame written on exit is the Beacons screen, at the window's size.
  const RgbImage last = testing::ReadPng((dir / "last.png").string());
  EXPECT_EQ(last.width, 1280);
  EXPECT_EQ(last.height, 800);
  EXPECT_TRUE(ShowsGoldenPart(last, beacons_golden, regions.both_rows, *dy)) << (dir / "last.png");
  EXPECT_TRUE(ShowsGoldenPart(last, beacons_golden, regions.heading, *dy)) << (dir / "last.png");
  if (!HasFailure()) fs::remove_all(dir);
}

/// A display number no X server uses here.
std::string MissingDisplay() {
  for (int n = 4242;; ++n) {
    const std::string number = std::to_string(n);
    if (!fs::exists("/tmp/.X11-unix/X" + number) && !fs::exists("/tmp/.X" + number + "-lock")) {
      return ":" + number;
    }
  }
}

TEST(StudioWindowTest, WithoutAReachableDisplayTheStudioRunsHeadlessAndSaysWhy) {
  const fs::path dir =
      fs::temp_directory_path() / ("recon-window-none-" + std::to_string(getpid()));
  fs::remove_all(dir);
  const std::string display = MissingDisplay();
  const testing::CommandResult r = testing::RunCommand(
      "DISPLAY=" + display + " XDG_CONFIG_HOME=" + (dir / "config").string() +
      " timeout -s KILL 120 " + RECON_STUDIO + " --session " + (dir / "session").string() +
      " --frames 3 --screenshot " + (dir / "last.png").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("recon-studio: headless (EGL): cannot open a desktop window"),
            std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find(display), std::string::npos) << "the reason names the display\n"
                                                       << r.output;
  EXPECT_EQ(r.output.find("window on display"), std::string::npos) << r.output;
  const RgbImage last = testing::ReadPng((dir / "last.png").string());
  EXPECT_EQ(last.width, 1280);
  EXPECT_EQ(last.height, 800);
  fs::remove_all(dir);
}

TEST(DesktopWindowTest, WithoutADisplayItIsAUserErrorNamingIt) {
  const std::string display = MissingDisplay();
  setenv("DISPLAY", display.c_str(), 1);
  try {
    DesktopWindow window({});
    FAIL() << "a window opened on " << display;
  } catch (const UserError& e) {
    EXPECT_NE(std::string(e.what()).find("cannot open a desktop window"), std::string::npos)
        << e.what();
    EXPECT_NE(std::string(e.what()).find(display), std::string::npos) << e.what();
  }
}

// A high-DPI desktop (its DPI setting, Xft.dpi, at twice the 96 of a plain screen) gets the
// studio at UI scale 2 without --ui-scale; a scale given wins; an absurd setting is held to the
// largest scale the studio draws.
TEST(DesktopWindowTest, TheUiScaleFollowsTheScreensUnlessOneIsGiven) {
  VirtualDisplay display;
  ASSERT_EQ(display.error(), "");
  setenv("DISPLAY", display.name().c_str(), 1);
  DesktopWindow::Options options;
  options.title = "scale test";
  options.renderer = {320, 200, 16.0f, 1.0f};
  options.ui_scale_from_screen = true;
  {
    DesktopWindow window(options);  // no DPI setting: a plain screen
    EXPECT_FLOAT_EQ(window.ui_scale(), 1.0f);
  }
  display.SetResources("Xft.dpi:\t192\n");
  {
    DesktopWindow window(options);
    EXPECT_FLOAT_EQ(window.ui_scale(), 2.0f);
  }
  options.ui_scale_from_screen = false;
  options.renderer.ui_scale = 1.5f;
  {
    DesktopWindow window(options);
    EXPECT_FLOAT_EQ(window.ui_scale(), 1.5f);
  }
  display.SetResources("Xft.dpi:\t960\n");
  options.ui_scale_from_screen = true;
  {
    DesktopWindow window(options);
    EXPECT_FLOAT_EQ(window.ui_scale(), options.max_ui_scale);
  }
}

/// What the test's window saw in its last frame.
struct Seen {
  std::string text;
  bool editing = false;
  bool entered = false;
  bool w_down = false;
  float width = 0, height = 0;
};

class DesktopWindowApiTest : public ::testing::TestWithParam<DesktopWindow::ContextApi> {};

TEST_P(DesktopWindowApiTest, TakesTypedTextHeldKeysResizeAndClose) {
  VirtualDisplay display;
  ASSERT_EQ(display.error(), "");
  setenv("DISPLAY", display.name().c_str(), 1);
  DesktopWindow::Options options;
  options.title = "desktop window test";
  options.renderer = {320, 200, 16.0f};
  options.context_api = GetParam();
  options.fall_back_to_glx = false;
  DesktopWindow window(options);
  const bool egl = GetParam() == DesktopWindow::ContextApi::kEgl;
  EXPECT_EQ(window.description().rfind(egl ? "EGL; OpenGL " : "GLX; OpenGL ", 0), 0u)
      << window.description();

  Seen seen;
  char buffer[64] = "";
  bool focus = true;
  const auto draw = [&] {
    const ImGuiIO& io = ImGui::GetIO();
    ImGui::SetNextWindowPos(ImVec2(0, 0));
    ImGui::SetNextWindowSize(io.DisplaySize);
    ImGui::Begin("test", nullptr, ImGuiWindowFlags_NoDecoration);
    if (focus) ImGui::SetKeyboardFocusHere();
    focus = false;
    ImGui::InputText("##text", buffer, sizeof(buffer));
    seen.editing = ImGui::IsItemActive();
    seen.text = buffer;
    seen.entered = seen.entered || ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Enter));
    // Letters ImGui 1.86 does not name are down in their ASCII slot.
    seen.w_down = ImGui::IsKeyDown('W');
    seen.width = io.DisplaySize.x;
    seen.height = io.DisplaySize.y;
    ImGui::End();
  };
  bool open = true;
  const auto frames_until = [&](const std::function<bool()>& done) {
    const auto deadline = Clock::now() + kDeadline;
    while (open && !done() && Clock::now() < deadline) open = window.Frame(draw);
    return done();
  };
  ASSERT_TRUE(window.Frame(draw));
  const unsigned long id = display.FindWindow("^desktop window test$");
  ASSERT_NE(id, 0u);
  const std::string xdotool = "xdotool ";
  const std::string target = " --window " + std::to_string(id);
  // The pointer in the window gives it the keyboard (Xvfb has no window manager).
  ASSERT_EQ(display.Run(xdotool + "mousemove" + target + " 160 150").exit_code, 0);

  ASSERT_TRUE(frames_until([&] { return seen.editing; })) << "the text field took no focus";
  ASSERT_EQ(display.Run(xdotool + "type hello").exit_code, 0);
  EXPECT_TRUE(frames_until([&] { return seen.text == "hello"; })) << "typed: " << seen.text;
  // Enter comes and goes between two frames: a key pressed this frame.
  ASSERT_EQ(display.Run(xdotool + "key Return").exit_code, 0);
  EXPECT_TRUE(frames_until([&] { return seen.entered; }));
  EXPECT_FALSE(seen.editing) << "Enter ends editing";

  ASSERT_EQ(display.Run(xdotool + "keydown w").exit_code, 0);
  EXPECT_TRUE(frames_until([&] { return seen.w_down; }));
  for (int i = 0; i < 3 && open; ++i) open = window.Frame(draw);
  EXPECT_TRUE(seen.w_down) << "a held key stays down from frame to frame";
  ASSERT_EQ(display.Run(xdotool + "keyup w").exit_code, 0);
  EXPECT_TRUE(frames_until([&] { return !seen.w_down; }));
  EXPECT_EQ(seen.text, "hello") << "keys after Enter do not type";

  // A resized window draws frames of its new size.
  ASSERT_EQ(display.Run(xdotool + "windowsize " + std::to_string(id) + " 400 300").exit_code, 0);
  EXPECT_TRUE(frames_until([&] { return seen.width == 400 && seen.height == 300; }))
      << seen.width << "x" << seen.height;
  // The screenshot is what the window shows.
  RgbImage shot = window.Screenshot();
  EXPECT_EQ(shot.width, 400);
  EXPECT_EQ(shot.height, 300);
  bool same = false;
  for (const auto deadline = Clock::now() + kDeadline; !same && Clock::now() < deadline;) {
    same = display.Grab(id).rgb == shot.rgb;
    if (!same && (open = window.Frame(draw))) shot = window.Screenshot();
  }
  EXPECT_TRUE(same) << "the screenshot differs from what the X server shows";

  display.RequestClose(id);
  EXPECT_TRUE(frames_until([&] { return !open; })) << "the window did not close";
  EXPECT_FALSE(window.Frame(draw)) << "a closed window stays closed";
}

// The window asks the window manager for the studio's smallest size (Xvfb has none to enforce
// it), and its close button asks the close guard: refused, the window stays and draws on.
TEST(DesktopWindowTest, HasAMinimumSizeAndItsCloseButtonAsksFirst) {
  VirtualDisplay display;
  ASSERT_EQ(display.error(), "");
  setenv("DISPLAY", display.name().c_str(), 1);
  DesktopWindow::Options options;
  options.title = "minimum size test";
  options.renderer = {1100, 700, 16.0f};
  options.min_width = 1024;
  options.min_height = 640;
  DesktopWindow window(options);
  int asked = 0;
  bool may_close = false;
  window.SetCloseGuard([&] {
    ++asked;
    return may_close;
  });
  const auto draw = [] {
    ImGui::Begin("test");
    ImGui::End();
  };
  ASSERT_TRUE(window.Frame(draw));
  const unsigned long id = display.FindWindow("^minimum size test$");
  ASSERT_NE(id, 0u);
  EXPECT_EQ(display.MinimumSize(id), std::make_pair(1024, 640));

  display.RequestClose(id);
  bool open = true;
  for (const auto deadline = Clock::now() + kDeadline; asked == 0 && Clock::now() < deadline;) {
    open = window.Frame(draw);
  }
  EXPECT_EQ(asked, 1);
  EXPECT_TRUE(open) << "refused, the close button closed the window anyway";
  for (int i = 0; i < 5 && open; ++i) open = window.Frame(draw);
  EXPECT_TRUE(open) << "the window closed later without being asked again";
  may_close = true;
  display.RequestClose(id);
  for (const auto deadline = Clock::now() + kDeadline; open && Clock::now() < deadline;) {
    open = window.Frame(draw);
  }
  EXPECT_FALSE(open) << "allowed, the window did not close";
  EXPECT_EQ(asked, 2);
}

INSTANTIATE_TEST_SUITE_P(ContextApis, DesktopWindowApiTest,
                         ::testing::Values(DesktopWindow::ContextApi::kEgl,
                                           DesktopWindow::ContextApi::kGlx),
                         [](const ::testing::TestParamInfo<DesktopWindow::ContextApi>& param) {
                           return param.param == DesktopWindow::ContextApi::kEgl ? "Egl" : "Glx";
                         });

}  // namespace
}  // namespace recon::ui
