// The host's side of the preview (preview_server.h): the plugin caligo_preview.so is loaded on
// the first --preview, so that cpp-httplib and its libraries stay out of every other run.
#include <cstdio>

#include "commands.h"
#include "core/error.h"
#include "core/message_text.h"
#include "core/module_loader.h"
#include "preview_plugin.h"
#include "preview_server.h"

namespace caligo {
namespace {

const PreviewPluginApi& preview_plugin() {
  try {
    return load_plugin<PreviewPluginApi>(kPreviewPluginName, kPreviewPluginSymbol, kPreviewPluginAbi,
                                         "needed by --preview");
  } catch (const std::runtime_error& e) {
    throw EnvironmentError(e.what());
  }
}

}  // namespace

PreviewServer::PreviewServer(int port, std::function<void()> on_stop, bool filmic) {
  std::string error;
  server_ = preview_plugin().start(port, std::move(on_stop), filmic, &url_, &error);
  if (!server_) throw EnvironmentError(error);
}

PreviewServer::~PreviewServer() { preview_plugin().stop(server_); }

std::string PreviewServer::url() const { return url_; }

void PreviewServer::publish(PreviewState state) { preview_plugin().publish(server_, &state); }

void PreviewServer::linger(double seconds) { preview_plugin().linger(server_, seconds); }

std::unique_ptr<PreviewServer> start_preview(const std::optional<std::string>& port, std::function<void()> on_stop,
                                             bool filmic) {
  if (!port) return nullptr;
  int number = 0;
  if (!port->empty()) {
    size_t used = 0;
    try {
      number = std::stoi(*port, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used != port->size() || number < 0 || number > 65535)
      throw InputError(kCommandLine, "--preview: expected a port number in [0, 65535], got " + quote_for_message(*port));
  }
  auto server = std::make_unique<PreviewServer>(number, std::move(on_stop), filmic);
  std::fprintf(stderr, "caligo: preview at %s\n", server->url().c_str());
  return server;
}

}  // namespace caligo
