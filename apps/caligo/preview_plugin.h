// The entry points of caligo_preview.so, the plugin that holds the preview server: cpp-httplib
// and what it links (OpenSSL, brotli, zlib: 13 shared objects) stay out of every run that does
// not ask for --preview (core/module_loader.h). Host and plugin are built together, so C++ types
// cross the boundary; exceptions do not: a failure to listen comes back as a message.
#pragma once

#include <functional>
#include <string>

#include "preview_server.h"

namespace caligo {

struct PreviewPluginApi {
  int abi_version;
  // A server listening on 127.0.0.1:port (0: any free port), or nullptr and `error`.
  void* (*start)(int port, std::function<void()> on_stop, bool filmic, std::string* url, std::string* error);
  void (*publish)(void* server, PreviewState* state);  // moves from *state
  void (*linger)(void* server, double seconds);
  void (*stop)(void* server);
};

inline constexpr int kPreviewPluginAbi = 1;
inline constexpr const char* kPreviewPluginName = "caligo_preview";
inline constexpr const char* kPreviewPluginSymbol = "caligo_preview_plugin";

}  // namespace caligo
