#pragma once

// MuJoCo models owned safely, with MuJoCo's errors turned into exceptions.
//
// MuJoCo's default error handler prints, waits for Enter and exits: in a headless run (CI, a
// batch experiment, the GUI's worker thread) that is a hang. Every use of MuJoCo in the project
// goes through this file, which installs handlers that throw instead.

#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

struct mjModel_;
struct mjData_;

namespace recon::worlds {

/// A MuJoCo error raised while simulating (mju_error), as an exception. Thrown from inside
/// MuJoCo's C code; the mjData it happened in must be reset before further use.
class MujocoError : public std::runtime_error {
 public:
  explicit MujocoError(const std::string& message) : std::runtime_error(message) {}
};

/// Makes mju_error throw MujocoError and mju_warning go to stderr once per message kind.
/// Idempotent and thread-safe; every constructor below calls it.
void InstallMujocoErrorHandlers();

/// A compiled model with one mjData. Move-only; frees both on destruction.
class MujocoModel {
 public:
  /// Loads and compiles an MJCF file. UserError naming the file and MuJoCo's message (which
  /// gives the element and line) if it is missing or invalid.
  static MujocoModel FromFile(const std::string& path);
  /// Compiles MJCF text; `name` is used in messages (e.g. "tabletop scene").
  static MujocoModel FromString(const std::string& xml, const std::string& name);
  /// Compiles `main_file` out of in-memory files {name, text}; <include file=".."/> resolves
  /// among them by name. Used for the scenes compiled into the program (scene_assets.h).
  static MujocoModel FromFiles(const std::vector<std::pair<std::string, std::string>>& files,
                               const std::string& main_file, const std::string& name);

  MujocoModel(MujocoModel&&) noexcept;
  MujocoModel& operator=(MujocoModel&&) noexcept;
  ~MujocoModel();

  const mjModel_* model() const { return model_.get(); }
  /// For set-up after compilation only (e.g. painting AprilTag bitmaps into textures before a
  /// renderer uploads them); never while another thread simulates or renders this model.
  mjModel_* mutable_model() { return model_.get(); }
  mjData_* data() { return data_.get(); }
  const mjData_* data() const { return data_.get(); }

 private:
  struct ModelDeleter {
    void operator()(mjModel_* m) const;
  };
  struct DataDeleter {
    void operator()(mjData_* d) const;
  };
  MujocoModel(mjModel_* model, const std::string& name);

  std::unique_ptr<mjModel_, ModelDeleter> model_;
  std::unique_ptr<mjData_, DataDeleter> data_;
};

}  // namespace recon::worlds
