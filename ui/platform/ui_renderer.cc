#include "ui/platform/ui_renderer.h"

#include <GL/gl.h>
#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>

#include <string>
#include <vector>

#include "engine/core/error.h"
#include "ui/platform/studio_font.h"
#include "ui/platform/studio_style.h"

namespace recon::ui {

UiRenderer::UiRenderer(const Options& options) : options_(options) {
  const char* renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  const char* version = reinterpret_cast<const char*>(glGetString(GL_VERSION));
  if (renderer == nullptr || version == nullptr) {
    throw UserError("the studio needs a current OpenGL context, and none is current");
  }
  gl_description_ = std::string("OpenGL ") + version + ", " + renderer;
  IMGUI_CHECKVERSION();
  context_ = ImGui::CreateContext();
  ImGui::SetCurrentContext(context_);
  ImGuiIO& io = ImGui::GetIO();
  io.IniFilename = nullptr;  // layout comes from code, never from a file left by a previous run
  io.LogFilename = nullptr;
  io.ConfigFlags |= ImGuiConfigFlags_NavEnableKeyboard;
  // ImGui 1.86 reads keys through KeyMap into KeysDown; map each named key to its own slot so
  // FrameInput::keys_pressed can carry ImGuiKey values directly.
  for (int key = 0; key < ImGuiKey_COUNT; ++key) io.KeyMap[key] = key;
  // One font, compiled into the program, at a pinned size: goldens must not depend on the
  // machine's fonts or ImGui's built-in bitmap font.
  ImFontConfig config;
  config.FontDataOwnedByAtlas = false;
  config.OversampleH = 2;
  config.OversampleV = 1;
  const StudioFontData font = StudioFont();
  io.Fonts->AddFontFromMemoryTTF(const_cast<unsigned char*>(font.data), static_cast<int>(font.size),
                                 options_.font_size_px * options_.ui_scale, &config);
  ApplyStudioStyle(ImGui::GetStyle());
  ImGui::GetStyle().ScaleAllSizes(options_.ui_scale);
  // GLSL 1.30 runs on Mesa's compatibility profile and on any desktop GL 3.0+ driver.
  if (!ImGui_ImplOpenGL3_Init("#version 130")) {
    ImGui::DestroyContext(context_);
    throw UserError("ImGui's OpenGL 3 renderer could not start on " + gl_description_);
  }
}

UiRenderer::~UiRenderer() {
  ImGui::SetCurrentContext(context_);
  ImGui_ImplOpenGL3_Shutdown();
  ImGui::DestroyContext(context_);
}

void UiRenderer::NewFrame(const FrameInput& input) {
  ImGui::SetCurrentContext(context_);
  ImGuiIO& io = ImGui::GetIO();
  io.DisplaySize = ImVec2(static_cast<float>(options_.width), static_cast<float>(options_.height));
  io.DisplayFramebufferScale = ImVec2(1.0f, 1.0f);
  io.DeltaTime = static_cast<float>(input.delta_s > 0 ? input.delta_s : 1.0 / 60.0);
  // ImGui 1.86 has no event queue: the state is set directly each frame.
  io.MousePos = ImVec2(input.mouse_x, input.mouse_y);
  for (int b = 0; b < 3; ++b) io.MouseDown[b] = input.mouse_down[b];
  io.MouseWheel = input.wheel;
  io.KeyCtrl = input.ctrl;
  io.KeyShift = input.shift;
  io.KeyAlt = input.alt;
  for (bool& down : io.KeysDown) down = false;
  // A key pressed this frame is down for one frame, a held one for as long as it is held.
  for (const std::vector<int>* keys : {&input.keys_pressed, &input.keys_down}) {
    for (int key : *keys) {
      if (key >= 0 && key < static_cast<int>(IM_ARRAYSIZE(io.KeysDown))) io.KeysDown[key] = true;
    }
  }
  for (unsigned c : input.characters) io.AddInputCharacter(c);
  ImGui_ImplOpenGL3_NewFrame();
  ImGui::NewFrame();
}

void UiRenderer::Render() {
  ImGui::SetCurrentContext(context_);
  ImGui::Render();
  DrawLastFrame();
}

void UiRenderer::DrawLastFrame() {
  ImGui::SetCurrentContext(context_);
  glViewport(0, 0, options_.width, options_.height);
  const ImVec4 clear = ImGui::GetStyle().Colors[ImGuiCol_WindowBg];
  glClearColor(clear.x, clear.y, clear.z, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT);
  // Null before the first Render and between NewFrame and Render.
  if (ImDrawData* draw_data = ImGui::GetDrawData()) ImGui_ImplOpenGL3_RenderDrawData(draw_data);
}

void UiRenderer::Resize(int width, int height) {
  if (width <= 0 || height <= 0) {
    throw UserError("the studio's frame size must be positive, not " + std::to_string(width) + "x" +
                    std::to_string(height));
  }
  options_.width = width;
  options_.height = height;
}

}  // namespace recon::ui
