#include "core/module_loader.h"

#include <dlfcn.h>

#include <filesystem>
#include <map>
#include <mutex>
#include <stdexcept>
#include <vector>

namespace caligo {
namespace {

std::vector<std::filesystem::path> module_dirs() {
  std::vector<std::filesystem::path> dirs;
  std::error_code ec;
  const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (!ec) dirs.push_back(exe.parent_path());
  // The shared object this code is linked into, when it is not the executable (the Python
  // module, installed with the plugins beside it).
  Dl_info self{};
  if (dladdr(reinterpret_cast<void*>(&module_dirs), &self) != 0 && self.dli_fname != nullptr) {
    const std::filesystem::path dir = std::filesystem::absolute(self.dli_fname, ec).parent_path();
    if (!ec && (dirs.empty() || !std::filesystem::equivalent(dirs.front(), dir, ec))) dirs.push_back(dir);
  }
#ifdef CALIGO_MODULE_DIR
  const std::filesystem::path build_dir = CALIGO_MODULE_DIR;
  if (dirs.empty() || !std::filesystem::equivalent(dirs.front(), build_dir, ec)) dirs.push_back(build_dir);
#endif
  return dirs;
}

void* open_module(const std::string& name, const char* purpose) {
  std::string tried;
  for (const std::filesystem::path& dir : module_dirs()) {
    const std::filesystem::path file = dir / (name + ".so");
    std::error_code ec;
    if (!std::filesystem::exists(file, ec)) {
      tried += "\n  " + file.string() + ": not found";
      continue;
    }
    if (void* handle = dlopen(file.c_str(), RTLD_NOW | RTLD_LOCAL)) return handle;
    tried += "\n  " + file.string() + ": " + dlerror();
  }
  throw std::runtime_error("cannot load the module " + name + ".so (" + purpose +
                           "); it belongs next to the caligo executable. Tried:" + tried);
}

}  // namespace

std::string module_search_path() {
  std::string path;
  for (const std::filesystem::path& dir : module_dirs()) {
    if (!path.empty()) path += ':';
    path += dir.string();
  }
  return path;
}

void* module_symbol(const std::string& name, const char* symbol, const char* purpose) {
  static std::mutex mutex;
  static std::map<std::string, void*> handles;
  void* handle = nullptr;
  {
    const std::lock_guard lock(mutex);
    auto it = handles.find(name);
    if (it == handles.end()) it = handles.emplace(name, open_module(name, purpose)).first;
    handle = it->second;
  }
  dlerror();
  void* address = dlsym(handle, symbol);
  if (address == nullptr)
    throw std::runtime_error("the module " + name + ".so (" + purpose + ") has no symbol " + symbol +
                             ": it does not match this caligo build");
  return address;
}

}  // namespace caligo
