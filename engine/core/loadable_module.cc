#include "engine/core/loadable_module.h"

#include <dlfcn.h>

#include <cstdlib>

#include "engine/core/error.h"

namespace recon {

std::string ModulePath(const char* environment_variable, const char* built_path) {
  const char* path = std::getenv(environment_variable);
  return path != nullptr && path[0] != '\0' ? path : built_path;
}

const void* LoadModuleTable(const LoadableModule& module, int interface_version) {
  const std::string where = module.description + " " + module.path;
  const std::string why = module.needed_by + "; ./scripts/build builds it";
  // RTLD_LOCAL: the libraries it links stay its own.
  void* handle = dlopen(module.path.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (handle == nullptr) {
    const char* error = dlerror();
    throw UserError("cannot load " + where + " (" + (error != nullptr ? error : "unknown error") +
                    "): " + why);
  }
  using Entry = const void* (*)();
  const auto entry = reinterpret_cast<Entry>(dlsym(handle, module.entry.c_str()));
  if (entry == nullptr) throw UserError(where + " has no " + module.entry + ": " + why);
  const void* table = entry();
  // Every table starts with its interface version (an int).
  const int version = table != nullptr ? *static_cast<const int*>(table) : 0;
  if (version != interface_version) {
    throw UserError(where + " was built for another version of recon (interface " +
                    std::to_string(version) + ", expected " + std::to_string(interface_version) +
                    "): " + why);
  }
  return table;
}

}  // namespace recon
