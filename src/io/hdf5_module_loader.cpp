// Finds and loads libimunoise_hdf5.so (see hdf5_module.hpp for why HDF5 is a module).
#include <dlfcn.h>

#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "hdf5_module.hpp"
#include "imunoise/error.hpp"

namespace imunoise::io::hdf5_module {
namespace {

namespace fs = std::filesystem;

// The program or shared object (e.g. the Python extension) this code was linked into.
fs::path own_object_dir() {
  Dl_info info{};
  if (dladdr(reinterpret_cast<void*>(&load), &info) == 0 || info.dli_fname == nullptr) return {};
  std::error_code ec;
  const fs::path object = fs::canonical(info.dli_fname, ec);
  return ec ? fs::path{} : object.parent_path();
}

fs::path executable_dir() {
  std::error_code ec;
  const fs::path self = fs::read_symlink("/proc/self/exe", ec);
  return ec ? fs::path{} : self.parent_path();
}

std::vector<fs::path> candidates() {
  if (const char* path = std::getenv("IMUNOISE_HDF5_MODULE"); path != nullptr && *path != '\0') {
    return {fs::path(path)};
  }
  std::vector<fs::path> out;
  for (const fs::path& dir : {own_object_dir(), executable_dir()}) {
    if (dir.empty()) continue;
    out.push_back(dir / kFileName);
    out.push_back(dir / ".." / IMUNOISE_INSTALL_LIBDIR / "imunoise" / kFileName);
  }
  out.emplace_back(IMUNOISE_HDF5_MODULE_BUILD_PATH);
  out.emplace_back(IMUNOISE_HDF5_MODULE_INSTALL_PATH);
  return out;
}

struct Loaded {
  const Api* api = nullptr;
  std::string failures;  // one line per place tried, when api is null
};

const Api* try_load(const fs::path& path, std::string& failures) {
  std::error_code ec;
  if (!fs::exists(path, ec)) {
    failures += "  " + path.string() + ": not there\n";
    return nullptr;
  }
  // Never closed: libhdf5 registers its own clean-up at exit.
  void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (handle == nullptr) {
    failures += "  " + path.string() + ": " + dlerror() + "\n";
    return nullptr;
  }
  auto entry = reinterpret_cast<EntryPoint>(dlsym(handle, kEntryPoint));
  const Api* api = entry != nullptr ? entry() : nullptr;
  if (api == nullptr || api->version != kVersion) {
    failures += "  " + path.string() + ": not a module of this imunoise build (stale?)\n";
    return nullptr;
  }
  return api;
}

Loaded load_once() {
  Loaded loaded;
  for (const fs::path& path : candidates()) {
    loaded.api = try_load(path, loaded.failures);
    if (loaded.api != nullptr) break;
  }
  return loaded;
}

}  // namespace

const Api& load(const std::string& source) {
  static const Loaded loaded = load_once();
  if (loaded.api == nullptr) {
    throw InputError(source + ": reading HDF5 needs the module " + std::string(kFileName) +
                     " (it links libhdf5), which could not be loaded from:\n" + loaded.failures +
                     "fix: install imunoise with its modules (cmake --install), or set "
                     "IMUNOISE_HDF5_MODULE=/path/to/" + kFileName +
                     " (and install libhdf5: apt install libhdf5-dev), or convert the file to text "
                     "or raw binary");
  }
  return *loaded.api;
}

}  // namespace imunoise::io::hdf5_module
