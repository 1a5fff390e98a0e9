#include "ui/platform/desktop_window.h"

// glBindFramebuffer is core GL 3.0; GLVND's libOpenGL exports it directly.
#define GL_GLEXT_PROTOTYPES 1
#include <GL/gl.h>
#include <GL/glext.h>
// After GL: GLFW would otherwise include its own GL header first.
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <imgui.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <utility>

#include "engine/core/error.h"
#include "ui/platform/offscreen_target.h"

namespace recon::ui {

// Letters are reported by their ASCII code as well (see FrameInput::keys_down): those slots of
// io.KeysDown must not be ones the renderer's identity KeyMap gives to a named ImGuiKey.
static_assert(ImGuiKey_COUNT <= 'A', "ImGuiKey values overlap the letters' ASCII slots");

namespace {

// GLFW reports errors through a callback, not return values; the last one becomes the message of
// the UserError the constructor throws. GLFW is used from the main thread only.
std::string& LastGlfwError() {
  static std::string error;
  return error;
}

void RecordGlfwError(int /*code*/, const char* description) {
  LastGlfwError() = description != nullptr ? description : "unknown GLFW error";
}

std::string TakeGlfwError(const char* what) {
  std::string error = std::move(LastGlfwError());
  LastGlfwError().clear();
  return std::string(what) + (error.empty() ? "" : ": " + error);
}

// GLFW allows one set of windows per process, and glfwTerminate closes them all.
std::atomic<bool> window_open{false};

/// The ImGuiKey value a GLFW key stands for, or -1 for keys ImGui 1.86 does not name.
int ImGuiKeyOf(int glfw_key) {
  // clang-format off
  static constexpr std::pair<int, int> kKeys[] = {
      {GLFW_KEY_TAB, ImGuiKey_Tab},            {GLFW_KEY_LEFT, ImGuiKey_LeftArrow},
      {GLFW_KEY_RIGHT, ImGuiKey_RightArrow},   {GLFW_KEY_UP, ImGuiKey_UpArrow},
      {GLFW_KEY_DOWN, ImGuiKey_DownArrow},     {GLFW_KEY_PAGE_UP, ImGuiKey_PageUp},
      {GLFW_KEY_PAGE_DOWN, ImGuiKey_PageDown}, {GLFW_KEY_HOME, ImGuiKey_Home},
      {GLFW_KEY_END, ImGuiKey_End},            {GLFW_KEY_INSERT, ImGuiKey_Insert},
      {GLFW_KEY_DELETE, ImGuiKey_Delete},      {GLFW_KEY_BACKSPACE, ImGuiKey_Backspace},
      {GLFW_KEY_SPACE, ImGuiKey_Space},        {GLFW_KEY_ENTER, ImGuiKey_Enter},
      {GLFW_KEY_ESCAPE, ImGuiKey_Escape},      {GLFW_KEY_KP_ENTER, ImGuiKey_KeyPadEnter},
      {GLFW_KEY_A, ImGuiKey_A},                {GLFW_KEY_C, ImGuiKey_C},
      {GLFW_KEY_V, ImGuiKey_V},                {GLFW_KEY_X, ImGuiKey_X},
      {GLFW_KEY_Y, ImGuiKey_Y},                {GLFW_KEY_Z, ImGuiKey_Z},
  };
  // clang-format on
  for (const auto& [glfw, imgui] : kKeys) {
    if (glfw == glfw_key) return imgui;
  }
  return -1;
}

/// The io.KeysDown slots a GLFW key sets: its ImGuiKey and, for a letter, its ASCII code (GLFW's
/// letter keys are their upper-case ASCII codes, named by their place on a US keyboard, which
/// is what W/A/S/D driving wants).
void AddKeySlots(int glfw_key, std::vector<int>& slots) {
  if (const int key = ImGuiKeyOf(glfw_key); key >= 0) slots.push_back(key);
  if (glfw_key >= GLFW_KEY_A && glfw_key <= GLFW_KEY_Z) slots.push_back(glfw_key);
  if (glfw_key == GLFW_KEY_F12) slots.push_back(kEmergencyStopKey);
}

const char* ContextApiName(int api) {
  if (api == GLFW_EGL_CONTEXT_API) return "EGL";
  if (api == GLFW_NATIVE_CONTEXT_API) return "GLX";  // GLFW's native API on X11
  return "OSMesa";
}

GLFWwindow* CreateWindow(const DesktopWindow::Options& options, int context_api) {
  glfwDefaultWindowHints();
  glfwWindowHint(GLFW_RESIZABLE, GLFW_TRUE);
  glfwWindowHint(GLFW_CLIENT_API, GLFW_OPENGL_API);
  glfwWindowHint(GLFW_CONTEXT_CREATION_API, context_api);
  // The renderer's shaders are GLSL 1.30 (GL 3.0). No profile is asked for: below 3.2 drivers
  // give their compatibility profile, the one the headless EGL context has too.
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 0);
  glfwWindowHint(GLFW_DEPTH_BITS, 24);
  glfwWindowHint(GLFW_STENCIL_BITS, 8);
  return glfwCreateWindow(options.renderer.width, options.renderer.height, options.title.c_str(),
                          nullptr, nullptr);
}

}  // namespace

struct DesktopWindow::Events {
  bool button_held[3] = {false, false, false};
  // A click can come and go between two frames (xdotool's always does): a press is shown to
  // ImGui for at least one frame, as ImGui's own GLFW backend does.
  bool button_pressed[3] = {false, false, false};
  double wheel = 0;
  std::vector<unsigned> characters;
  std::vector<int> keys_held;     // GLFW keys
  std::vector<int> keys_pressed;  // GLFW keys
  int pressed_mods = 0;           // modifiers of this frame's key presses (ctrl+c in one go)

  static Events& Of(GLFWwindow* window) {
    return *static_cast<Events*>(glfwGetWindowUserPointer(window));
  }
  static void OnMouseButton(GLFWwindow* window, int button, int action, int /*mods*/) {
    if (button < 0 || button >= 3) return;
    Events& e = Of(window);
    e.button_held[button] = action == GLFW_PRESS;
    if (action == GLFW_PRESS) e.button_pressed[button] = true;
  }
  static void OnScroll(GLFWwindow* window, double /*x*/, double y) { Of(window).wheel += y; }
  static void OnCharacter(GLFWwindow* window, unsigned code_point) {
    Of(window).characters.push_back(code_point);
  }
  static void OnKey(GLFWwindow* window, int key, int /*scancode*/, int action, int mods) {
    Events& e = Of(window);
    // Repeats are ImGui's business (it repeats held keys itself).
    if (action == GLFW_PRESS) {
      e.keys_pressed.push_back(key);
      e.pressed_mods |= mods;
      if (std::find(e.keys_held.begin(), e.keys_held.end(), key) == e.keys_held.end()) {
        e.keys_held.push_back(key);
      }
    } else if (action == GLFW_RELEASE) {
      e.keys_held.erase(std::remove(e.keys_held.begin(), e.keys_held.end(), key),
                        e.keys_held.end());
    }
  }
};

DesktopWindow::DesktopWindow(const Options& options) : events_(std::make_unique<Events>()) {
  if (options.max_frames_per_second <= 0) {
    throw UserError("the desktop window's frame rate cap must be positive");
  }
  frame_period_s_ = 1.0 / options.max_frames_per_second;
  if (window_open.exchange(true)) {
    throw UserError("cannot open a second desktop window: GLFW allows one per process here");
  }
  glfwSetErrorCallback(RecordGlfwError);
  if (glfwInit() != GLFW_TRUE) {
    window_open = false;
    throw UserError(TakeGlfwError("cannot open a desktop window"));
  }
  const int first_api =
      options.context_api == ContextApi::kEgl ? GLFW_EGL_CONTEXT_API : GLFW_NATIVE_CONTEXT_API;
  window_ = CreateWindow(options, first_api);
  std::string failures;
  if (window_ == nullptr) {
    failures = TakeGlfwError((std::string("no ") + ContextApiName(first_api) + " context").c_str());
    if (first_api == GLFW_EGL_CONTEXT_API && options.fall_back_to_glx) {
      window_ = CreateWindow(options, GLFW_NATIVE_CONTEXT_API);
      if (window_ == nullptr) failures += "; " + TakeGlfwError("no GLX context");
    }
  }
  if (window_ == nullptr) {
    glfwTerminate();
    window_open = false;
    throw UserError("cannot open a desktop window with an OpenGL 3 context: " + failures);
  }
  glfwMakeContextCurrent(window_);
  // Where the driver syncs to the display this paces frames; where it cannot, the cap does.
  glfwSwapInterval(1);
  glfwSetWindowUserPointer(window_, events_.get());
  glfwSetMouseButtonCallback(window_, Events::OnMouseButton);
  glfwSetScrollCallback(window_, Events::OnScroll);
  glfwSetCharCallback(window_, Events::OnCharacter);
  glfwSetKeyCallback(window_, Events::OnKey);
  try {
    UiRenderer::Options renderer_options = options.renderer;
    glfwGetFramebufferSize(window_, &renderer_options.width, &renderer_options.height);
    if (options.ui_scale_from_screen) {
      float x_scale = 1.0f, y_scale = 1.0f;
      glfwGetWindowContentScale(window_, &x_scale, &y_scale);
      const float screen = std::isfinite(y_scale) && y_scale > 0 ? y_scale : 1.0f;
      renderer_options.ui_scale = std::clamp(screen, options.min_ui_scale, options.max_ui_scale);
    }
    renderer_ = std::make_unique<UiRenderer>(renderer_options);
  } catch (...) {
    glfwDestroyWindow(window_);
    glfwTerminate();
    window_open = false;
    throw;
  }
  if (options.min_width > 0 && options.min_height > 0) {
    // GLFW's limits are in window coordinates, the layout's in framebuffer pixels.
    int window_width = 0, window_height = 0, framebuffer_width = 0, framebuffer_height = 0;
    glfwGetWindowSize(window_, &window_width, &window_height);
    glfwGetFramebufferSize(window_, &framebuffer_width, &framebuffer_height);
    const float per_pixel =
        framebuffer_width > 0 ? static_cast<float>(window_width) / framebuffer_width : 1.0f;
    const float scale = renderer_->ui_scale() * per_pixel;
    glfwSetWindowSizeLimits(window_, static_cast<int>(std::ceil(options.min_width * scale)),
                            static_cast<int>(std::ceil(options.min_height * scale)), GLFW_DONT_CARE,
                            GLFW_DONT_CARE);
  }
  description_ =
      std::string(ContextApiName(glfwGetWindowAttrib(window_, GLFW_CONTEXT_CREATION_API))) + "; " +
      renderer_->gl_description();
  // Copy and paste in text fields go through the desktop's clipboard.
  ImGuiIO& io = ImGui::GetIO();
  io.ClipboardUserData = window_;
  io.SetClipboardTextFn = [](void* window, const char* text) {
    glfwSetClipboardString(static_cast<GLFWwindow*>(window), text);
  };
  io.GetClipboardTextFn = [](void* window) {
    return glfwGetClipboardString(static_cast<GLFWwindow*>(window));
  };
}

DesktopWindow::~DesktopWindow() {
  glfwMakeContextCurrent(window_);  // the renderer frees GL objects of this context
  renderer_.reset();
  glfwDestroyWindow(window_);
  glfwTerminate();
  window_open = false;
}

FrameInput DesktopWindow::TakeInput(int window_width, int window_height, int framebuffer_width,
                                    int framebuffer_height) {
  Events& e = *events_;
  FrameInput input;
  bool any_button = false;
  for (int b = 0; b < 3; ++b) {
    input.mouse_down[b] = e.button_held[b] || e.button_pressed[b];
    any_button = any_button || input.mouse_down[b];
    e.button_pressed[b] = false;
  }
  // ImGui works in framebuffer pixels; the cursor comes in window coordinates (they differ on
  // high-DPI screens).
  double x = 0, y = 0;
  glfwGetCursorPos(window_, &x, &y);
  const bool inside = x >= 0 && y >= 0 && x < window_width && y < window_height;
  if ((inside || any_button) && window_width > 0 && window_height > 0) {
    input.mouse_x = static_cast<float>(x * framebuffer_width / window_width);
    input.mouse_y = static_cast<float>(y * framebuffer_height / window_height);
  }
  input.wheel = static_cast<float>(e.wheel);
  e.wheel = 0;
  input.characters = std::move(e.characters);
  e.characters.clear();
  for (int key : e.keys_pressed) AddKeySlots(key, input.keys_pressed);
  for (int key : e.keys_held) AddKeySlots(key, input.keys_down);
  e.keys_pressed.clear();
  const auto held = [&](int a, int b) {
    return glfwGetKey(window_, a) == GLFW_PRESS || glfwGetKey(window_, b) == GLFW_PRESS;
  };
  input.ctrl = held(GLFW_KEY_LEFT_CONTROL, GLFW_KEY_RIGHT_CONTROL) ||
               (e.pressed_mods & GLFW_MOD_CONTROL) != 0;
  input.shift =
      held(GLFW_KEY_LEFT_SHIFT, GLFW_KEY_RIGHT_SHIFT) || (e.pressed_mods & GLFW_MOD_SHIFT) != 0;
  input.alt = held(GLFW_KEY_LEFT_ALT, GLFW_KEY_RIGHT_ALT) || (e.pressed_mods & GLFW_MOD_ALT) != 0;
  e.pressed_mods = 0;
  return input;
}

float DesktopWindow::ui_scale() const { return renderer_->ui_scale(); }

bool DesktopWindow::Frame(const std::function<void()>& draw) {
  if (glfwGetCurrentContext() != window_) glfwMakeContextCurrent(window_);
  // Sleep until the frame is due, unless input arrives first: a click is answered at once.
  const double wait_s = last_frame_s_ < 0 ? 0 : last_frame_s_ + frame_period_s_ - glfwGetTime();
  if (wait_s > 0) {
    glfwWaitEventsTimeout(wait_s);
  } else {
    glfwPollEvents();
  }
  if (glfwWindowShouldClose(window_)) {
    if (!may_close_ || may_close_()) return false;
    glfwSetWindowShouldClose(window_, GLFW_FALSE);  // asked: the window stays until answered
  }
  int window_width = 0, window_height = 0, framebuffer_width = 0, framebuffer_height = 0;
  glfwGetWindowSize(window_, &window_width, &window_height);
  glfwGetFramebufferSize(window_, &framebuffer_width, &framebuffer_height);
  const double now_s = glfwGetTime();
  // Minimised: nothing to draw into. Input waits for the window to come back.
  if (framebuffer_width <= 0 || framebuffer_height <= 0) {
    last_frame_s_ = now_s;
    return true;
  }
  if (framebuffer_width != renderer_->width() || framebuffer_height != renderer_->height()) {
    renderer_->Resize(framebuffer_width, framebuffer_height);
  }
  FrameInput input = TakeInput(window_width, window_height, framebuffer_width, framebuffer_height);
  // Real time between frames: animations and ImGui's key repeat follow the clock.
  input.delta_s = last_frame_s_ < 0 ? 1.0 / 60.0 : std::max(now_s - last_frame_s_, 1e-4);
  last_frame_s_ = now_s;
  renderer_->NewFrame(input);
  draw();
  glBindFramebuffer(GL_FRAMEBUFFER, 0);  // the window's own framebuffer
  renderer_->Render();
  glfwSwapBuffers(window_);
  ++frames_;
  return true;
}

RgbImage DesktopWindow::Screenshot() {
  if (frames_ == 0) return {};
  if (glfwGetCurrentContext() != window_) glfwMakeContextCurrent(window_);
  OffscreenTarget target(renderer_->width(), renderer_->height());
  target.Bind();
  renderer_->DrawLastFrame();
  RgbImage image = target.Read();
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  return image;
}

}  // namespace recon::ui
