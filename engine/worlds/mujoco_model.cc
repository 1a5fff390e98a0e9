#include "engine/worlds/mujoco_model.h"

#include <mujoco/mujoco.h>

#include <cstdio>
#include <cstring>
#include <filesystem>
#include <mutex>
#include <vector>

#include "engine/core/error.h"
#include "engine/core/files.h"

namespace recon::worlds {

namespace {

constexpr int kErrorBufferSize = 1024;

void ThrowMujocoError(const char* message) {
  // MuJoCo documents that mju_error does not return; throwing unwinds through its C frames,
  // which x86-64 Linux builds carry unwind tables for (tests/worlds/mujoco_model_test.cc checks).
  throw MujocoError(std::string("MuJoCo error: ") + (message != nullptr ? message : ""));
}

void PrintMujocoWarning(const char* message) {
  std::fprintf(stderr, "MuJoCo warning: %s\n", message != nullptr ? message : "");
}

std::string Trimmed(const char* text) {
  std::string s(text);
  while (!s.empty() && (s.back() == '\n' || s.back() == ' ')) s.pop_back();
  return s;
}

}  // namespace

void InstallMujocoErrorHandlers() {
  static std::once_flag once;
  std::call_once(once, [] {
    mju_user_error = ThrowMujocoError;
    mju_user_warning = PrintMujocoWarning;
  });
}

void MujocoModel::ModelDeleter::operator()(mjModel_* m) const { mj_deleteModel(m); }
void MujocoModel::DataDeleter::operator()(mjData_* d) const { mj_deleteData(d); }

MujocoModel::MujocoModel(mjModel_* model, const std::string& name) : model_(model) {
  data_.reset(mj_makeData(model_.get()));
  if (!data_) throw UserError(name + ": MuJoCo could not allocate the simulation data");
}

MujocoModel::MujocoModel(MujocoModel&&) noexcept = default;
MujocoModel& MujocoModel::operator=(MujocoModel&&) noexcept = default;
MujocoModel::~MujocoModel() = default;

MujocoModel MujocoModel::FromFile(const std::string& path) {
  InstallMujocoErrorHandlers();
  RefuseNonRegularFile(path);
  if (!std::filesystem::is_regular_file(path)) {
    throw UserError("MJCF file " + path + " does not exist");
  }
  char error[kErrorBufferSize] = "";
  mjModel* model = mj_loadXML(path.c_str(), nullptr, error, sizeof(error));
  if (model == nullptr) throw UserError("MJCF file " + path + " is invalid: " + Trimmed(error));
  return MujocoModel(model, path);
}

MujocoModel MujocoModel::FromString(const std::string& xml, const std::string& name) {
  return FromFiles({{"model.xml", xml}}, "model.xml", name);
}

MujocoModel MujocoModel::FromFiles(const std::vector<std::pair<std::string, std::string>>& files,
                                   const std::string& main_file, const std::string& name) {
  InstallMujocoErrorHandlers();
  // mjVFS holds 2,000 fixed-size names (about 2 MB): keep it off the stack.
  auto vfs = std::make_unique<mjVFS>();
  mj_defaultVFS(vfs.get());
  struct VfsGuard {
    mjVFS* vfs;
    ~VfsGuard() { mj_deleteVFS(vfs); }
  } guard{vfs.get()};
  for (const auto& [file_name, text] : files) {
    if (mj_makeEmptyFileVFS(vfs.get(), file_name.c_str(), static_cast<int>(text.size())) != 0) {
      throw UserError(name + ": cannot stage " + file_name + " for MuJoCo");
    }
    std::memcpy(vfs->filedata[mj_findFileVFS(vfs.get(), file_name.c_str())], text.data(),
                text.size());
  }
  char error[kErrorBufferSize] = "";
  mjModel* model = mj_loadXML(main_file.c_str(), vfs.get(), error, sizeof(error));
  if (model == nullptr) throw UserError(name + " is not valid MJCF: " + Trimmed(error));
  return MujocoModel(model, name);
}

}  // namespace recon::worlds
