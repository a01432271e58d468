// Optional heavy libraries as plugins loaded on first use. OpenImageIO (~260 shared libraries,
// ~0.2–0.45 s and ~100 MB (docs/benchmarks.md) before main), OpenVDB (~30 ms, ~28 MB) and assimp would otherwise be
// loaded and relocated by every process, including `caligo --help`. Each lives in a small
// module built by this project (caligo_oiio.so, caligo_vdb.so, caligo_assimp.so) that exports
// one C function returning a table of entry points; only runs that read images, OpenVDB grids
// or PLY/COLLADA meshes load it.
//
// Modules are looked for next to the running executable (the directory of /proc/self/exe),
// then in the build tree's module directory (so test binaries in other folders find them).
// Thread safety: may be called concurrently; each module is opened once per process and never
// closed.
#pragma once

#include <stdexcept>
#include <string>

namespace caligo {

// The address of `symbol` in module `name` (without ".so"), loading the module on first use.
// `purpose` completes the error message ("needed to read OpenVDB files"). A missing module or
// symbol throws std::runtime_error naming the module, the places searched and dlerror().
void* module_symbol(const std::string& name, const char* symbol, const char* purpose);

// Where the modules are looked for, in order.
std::string module_search_path();

// A plugin's table of entry points: `symbol` is a C function of module `name` returning a
// const Api* whose first member is `abi_version`, which must equal `abi` (the module was built
// with the same headers). Throws std::runtime_error naming the module and `purpose` otherwise.
template <class Api>
const Api& load_plugin(const char* name, const char* symbol, int abi, const char* purpose) {
  using Entry = const Api* (*)();
  const auto entry = reinterpret_cast<Entry>(module_symbol(name, symbol, purpose));
  const Api* api = entry();
  if (api->abi_version != abi)
    throw std::runtime_error(std::string("the module ") + name + ".so (" + purpose + ") does not match this caligo build");
  return *api;
}

}  // namespace caligo
