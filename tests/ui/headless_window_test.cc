#include "ui/platform/headless_window.h"

#include <gtest/gtest.h>
#include <imgui.h>

#include <set>

namespace recon::ui {
namespace {

/// Pixels of `image` inside the rectangle, as 0xRRGGBB.
std::set<uint32_t> Colours(const RgbImage& image, int x0, int y0, int x1, int y1) {
  std::set<uint32_t> colours;
  for (int y = y0; y < y1; ++y) {
    for (int x = x0; x < x1; ++x) {
      const uint8_t* p = image.Pixel(y, x);
      colours.insert((p[0] << 16) | (p[1] << 8) | p[2]);
    }
  }
  return colours;
}

TEST(HeadlessWindowTest, DrawsImGuiIntoAnImageOfTheWindowsSize) {
  HeadlessWindow window({320, 200, 16.0f});
  bool clicked = false;
  ImVec2 button_min, button_max;
  const auto draw = [&] {
    ImGui::SetNextWindowPos(ImVec2(0, 0));
    ImGui::SetNextWindowSize(ImVec2(320, 200));
    ImGui::Begin("test", nullptr, ImGuiWindowFlags_NoDecoration);
    ImGui::TextUnformatted("Hello, teacher");
    clicked = ImGui::Button("Record") || clicked;
    button_min = ImGui::GetItemRectMin();
    button_max = ImGui::GetItemRectMax();
    ImGui::End();
  };
  window.Frame({}, draw);
  const RgbImage image = window.Screenshot();
  ASSERT_EQ(image.width, 320);
  ASSERT_EQ(image.height, 200);
  // Text was drawn: the first line holds more than background and one colour.
  EXPECT_GT(Colours(image, 10, 8, 200, 30).size(), 4u);
  // A click in the button's middle (press one frame, release the next) reaches ImGui.
  FrameInput press;
  press.mouse_x = (button_min.x + button_max.x) / 2;
  press.mouse_y = (button_min.y + button_max.y) / 2;
  press.mouse_down[0] = true;
  window.Frame(press, draw);
  FrameInput release = press;
  release.mouse_down[0] = false;
  window.Frame(release, draw);
  EXPECT_TRUE(clicked);
  // The same input gives the same pixels (the goldens rely on it).
  window.Frame({}, draw);
  const RgbImage again = window.Screenshot();
  window.Frame({}, draw);
  EXPECT_EQ(window.Screenshot().rgb, again.rgb);
}

}  // namespace
}  // namespace recon::ui
