#include "preview_server.h"

#include <httplib.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <mutex>
#include <random>
#include <thread>

#include <nlohmann/json.hpp>

#include "core/error.h"
#include "image/png_io.h"
#include "image/tonemap.h"
#include "preview_page.h"
#include "preview_plugin.h"

namespace caligo {
namespace {

constexpr size_t kMaxRequestBytes = 4096;

std::string random_token() {
  std::random_device device;
  static constexpr char kHex[] = "0123456789abcdef";
  std::string token;
  for (int i = 0; i < 32; ++i) token += kHex[device() & 15u];
  return token;
}

}  // namespace

struct HttpPreview {  // the plugin's server (preview_plugin.h)
  httplib::Server server;
  std::thread thread;
  std::string token;
  int port = 0;
  bool filmic = true;
  std::function<void()> on_stop;
  std::atomic<bool> stopping{false};
  std::mutex mutex;  // guards state and version
  PreviewState state;
  int version = -1;
  int shown = -2;  // the newest version a page fetched (-2: no page has asked for anything)

  bool allowed(const httplib::Request& req, httplib::Response& res) const {
    if (req.get_param_value("token") == token) return true;
    res.status = 403;
    res.set_content("forbidden: the preview's token is missing or wrong\n", "text/plain");
    return false;
  }
  void status(httplib::Response& res) {
    std::lock_guard lock(mutex);
    const double eta = state.done > 0 && !state.finished
                           ? state.seconds / state.done * double(state.target - state.done) : -1.0;
    const nlohmann::json j = {{"version", version},   {"done", state.done},     {"target", state.target},
                              {"seconds", state.seconds}, {"eta", eta},         {"finished", state.finished},
                              {"stopping", stopping.load()}, {"layers", preview_layers(state.image)},
                              {"table", state.table}, {"unit", state.table.empty() ? "spp" : "frames"}};
    res.set_content(j.dump(), "application/json");
  }
  void image(const httplib::Request& req, httplib::Response& res) {
    float exposure = 0.0f;
    try {
      if (req.has_param("exposure")) exposure = std::stof(req.get_param_value("exposure"));
    } catch (const std::exception&) {
      exposure = NAN;
    }
    if (!std::isfinite(exposure) || std::abs(exposure) > 64.0f) {
      res.status = 400;
      res.set_content("exposure: expected stops in [-64, 64]\n", "text/plain");
      return;
    }
    std::optional<Image> layer;
    {
      std::lock_guard lock(mutex);
      try {
        if (req.has_param("v")) shown = std::max(shown, std::stoi(req.get_param_value("v")));
      } catch (const std::exception&) {
      }
      layer = preview_layer(state.image, req.has_param("layer") ? req.get_param_value("layer") : "beauty");
    }
    if (!layer) {
      res.status = 404;
      res.set_content("no such layer\n", "text/plain");
      return;
    }
    const std::vector<uint8_t> rgb = to_srgb8_preview(*layer, PreviewSettings{exposure, filmic});
    res.set_content(encode_png(layer->width(), layer->height(), rgb), "image/png");
    res.set_header("Cache-Control", "no-store");
  }
};

namespace {

// The plugin's server: Impl, with the constructor's work.
void* start(int port, std::function<void()> on_stop, bool filmic, std::string* url, std::string* error) {
  auto impl = std::make_unique<HttpPreview>();
  HttpPreview& m = *impl;
  m.token = random_token();
  m.filmic = filmic;
  m.on_stop = std::move(on_stop);
  m.server.set_payload_max_length(kMaxRequestBytes);
  m.server.set_read_timeout(5, 0);
  m.server.set_write_timeout(5, 0);
  m.server.Get("/", [&m](const httplib::Request& req, httplib::Response& res) {
    if (m.allowed(req, res)) res.set_content(kPreviewPage, "text/html; charset=utf-8");
  });
  m.server.Get("/status", [&m](const httplib::Request& req, httplib::Response& res) {
    if (!m.allowed(req, res)) return;
    {
      std::lock_guard lock(m.mutex);
      m.shown = std::max(m.shown, -1);  // a page is open
    }
    m.status(res);
  });
  m.server.Get("/image.png", [&m](const httplib::Request& req, httplib::Response& res) {
    if (m.allowed(req, res)) m.image(req, res);
  });
  m.server.Post("/stop", [&m](const httplib::Request& req, httplib::Response& res) {
    if (!m.allowed(req, res)) return;
    if (!m.stopping.exchange(true) && m.on_stop) m.on_stop();
    res.set_content("{\"stopping\": true}", "application/json");
  });
  m.port = port > 0 ? (m.server.bind_to_port("127.0.0.1", port) ? port : -1) : m.server.bind_to_any_port("127.0.0.1");
  if (m.port <= 0) {
    *error = "--preview: cannot listen on 127.0.0.1:" + std::to_string(port) + " (in use, or not allowed)";
    return nullptr;
  }
  m.thread = std::thread([&m] { m.server.listen_after_bind(); });
  *url = "http://127.0.0.1:" + std::to_string(m.port) + "/?token=" + m.token;
  return impl.release();
}

void stop(void* server) {
  auto* m = static_cast<HttpPreview*>(server);
  m->server.stop();
  if (m->thread.joinable()) m->thread.join();
  delete m;
}

void linger(void* server, double seconds) {
  HttpPreview* impl_ = static_cast<HttpPreview*>(server);
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  while (std::chrono::steady_clock::now() < end) {
    {
      std::lock_guard lock(impl_->mutex);
      if (impl_->shown == -2 || impl_->shown >= impl_->version) return;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
}

void publish(void* server, PreviewState* state) {
  auto* m = static_cast<HttpPreview*>(server);
  std::lock_guard lock(m->mutex);
  m->state = std::move(*state);
  ++m->version;
}

}  // namespace
}  // namespace caligo

extern "C" __attribute__((visibility("default"))) const caligo::PreviewPluginApi* caligo_preview_plugin() {
  static const caligo::PreviewPluginApi api{caligo::kPreviewPluginAbi, &caligo::start, &caligo::publish,
                                            &caligo::linger, &caligo::stop};
  return &api;
}
