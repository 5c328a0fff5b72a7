#include "live_viewer.hpp"

#include <httplib.h>
#include <spdlog/spdlog.h>

#include <stdexcept>

namespace mrslam::fusion {

namespace {

constexpr int kServerThreads = 4;  ///< a few browsers at once; each request is short

void sendPng(httplib::Response& response, const std::vector<std::uint8_t>& png) {
  response.set_header("Cache-Control", "no-store");
  response.set_content(reinterpret_cast<const char*>(png.data()), png.size(), "image/png");
}

void sendNotFound(httplib::Response& response, const std::string& what) {
  response.status = 404;
  response.set_content(what + "\n", "text/plain");
}

}  // namespace

LiveViewer::LiveViewer(const ViewerSettings& settings, const ViewerModel& model)
    : settings_(settings), model_(model), server_(std::make_unique<httplib::Server>()) {
  server_->new_task_queue = [] { return new httplib::ThreadPool(kServerThreads); };
  addRoutes();
  if (settings_.port == 0) {
    port_ = server_->bind_to_any_port(settings_.host);
  } else if (server_->bind_to_port(settings_.host, settings_.port)) {
    port_ = settings_.port;
  } else {
    port_ = -1;
  }
  if (port_ <= 0) {
    throw std::runtime_error("viewer: cannot listen on " + settings_.host + ":" +
                             std::to_string(settings_.port));
  }
  thread_ = std::thread([this] { server_->listen_after_bind(); });
  spdlog::info("fusion: live viewer at {}", url());
}

LiveViewer::~LiveViewer() {
  server_->stop();
  if (thread_.joinable()) {
    thread_.join();
  }
}

std::string LiveViewer::url() const {
  return "http://" + settings_.host + ":" + std::to_string(port_) + "/";
}

void LiveViewer::addRoutes() {
  server_->Get("/", [](const httplib::Request&, httplib::Response& response) {
    response.set_content(viewerPage(), "text/html; charset=utf-8");
  });
  server_->Get("/api/state", [this](const httplib::Request&, httplib::Response& response) {
    response.set_header("Cache-Control", "no-store");
    response.set_content(model_.stateJson(), "application/json");
  });
  server_->Get("/api/global.png", [this](const httplib::Request&, httplib::Response& response) {
    const std::vector<std::uint8_t> png = model_.globalMapPng();
    if (png.empty()) {
      sendNotFound(response, "no global map yet");
      return;
    }
    sendPng(response, png);
  });
  server_->Get(R"(/api/robot/([A-Za-z0-9_-]{1,64})\.png)",
               [this](const httplib::Request& request, httplib::Response& response) {
                 const auto png = model_.robotMapPng(request.matches[1].str());
                 if (!png) {
                   sendNotFound(response, "no map of robot " + request.matches[1].str());
                   return;
                 }
                 sendPng(response, *png);
               });
}

}  // namespace mrslam::fusion
