#include <stdexcept>

#include "core/module_loader.h"
#include "image/oiio_plugin.h"

namespace caligo {

const OiioPluginApi& oiio_plugin(const char* purpose) {
  return load_plugin<OiioPluginApi>(kOiioPluginName, kOiioPluginSymbol, kOiioPluginAbi, purpose);
}

}  // namespace caligo
