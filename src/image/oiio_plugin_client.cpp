#include <stdexcept>

#include "core/module_loader.h"
#include "image/oiio_plugin.h"

namespace caligo {

const OiioPluginApi& oiio_plugin(const char* purpose) {
  using Entry = const OiioPluginApi* (*)();
  const auto entry = reinterpret_cast<Entry>(module_symbol(kOiioPluginName, kOiioPluginSymbol, purpose));
  const OiioPluginApi* api = entry();
  if (api->abi_version != kOiioPluginAbi)
    throw std::runtime_error(std::string("the module ") + kOiioPluginName + ".so (" + purpose +
                             ") does not match this caligo build");
  return *api;
}

}  // namespace caligo
