#include "app/studio/cell_view.h"

#include <array>
#include <string>

#include "devices/cell/scene_camera.h"

namespace recon::studio {

void ShowTabletopView(worlds::Tabletop& world, worlds::SceneRenderer& renderer, int width,
                      int height, const store::SessionManifest& manifest,
                      const std::vector<float>& reading, ui::StudioSnapshot& s) {
  constexpr char kCamera[] = "top";
  s.camera = renderer.Render(world.scene(), kCamera, width, height);
  const tags::PinholeCamera camera = cell::SceneCamera(world.scene(), kCamera, width, height);
  const auto pixel = [&](const Eigen::Vector3d& p) {
    const Eigen::Vector2d px = camera.Project(p);
    return std::array<float, 2>{static_cast<float>(px.x()), static_cast<float>(px.y())};
  };
  const auto object = [&](const std::string& name, const Eigen::Vector3d& p) {
    const std::array<float, 2> px = pixel(p);
    s.objects.push_back({name, px[0], px[1]});
  };
  object("plate", world.PlatePosition());
  object("bowl", world.BowlPosition());
  object("toast", world.ToastPosition());
  for (const BeaconSpec& b : manifest.beacons) {
    ui::BeaconView view;
    view.name = b.name;
    auto it = manifest.beacon_assignments.find(b.name);
    view.object = it == manifest.beacon_assignments.end() ? "" : it->second;
    view.quantity = b.quantity;
    view.unit = b.unit;
    view.reading = reading;
    view.pixel = pixel(world.BeaconPosition());
    view.rate_hz = 1.0 / world.StepSeconds();
    view.noise_m = manifest.beacon_noise_sigma;
    s.beacons.push_back(view);
  }
}

}  // namespace recon::studio
