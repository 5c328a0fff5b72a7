#pragma once
// The live viewer's HTTP server (cpp-httplib) on a thread of its own:
//   GET /                      the page (it polls the state and redraws, no reload needed)
//   GET /api/state             the ViewerModel's state document (JSON)
//   GET /api/global.png        the global map with the robots' cells and trajectories
//   GET /api/robot/<id>.png    one robot's own map
// A port that cannot be bound is an error at start; the server stops with the object.

#include <memory>
#include <string>
#include <thread>

#include "mrslam/fusion/fusion_config.hpp"
#include "mrslam/fusion/viewer_model.hpp"

namespace httplib {
class Server;
}

namespace mrslam::fusion {

class LiveViewer {
 public:
  /// Binds host:port (port 0: any free port) and starts serving; throws std::runtime_error when
  /// the address cannot be bound.
  LiveViewer(const ViewerSettings& settings, const ViewerModel& model);
  ~LiveViewer();
  LiveViewer(const LiveViewer&) = delete;
  LiveViewer& operator=(const LiveViewer&) = delete;

  /// The port it listens on.
  int port() const { return port_; }
  /// http://host:port/
  std::string url() const;

 private:
  void addRoutes();

  const ViewerSettings settings_;
  const ViewerModel& model_;
  std::unique_ptr<httplib::Server> server_;
  int port_ = 0;
  std::thread thread_;
};

/// The page: HTML, CSS and JavaScript in one document.
const char* viewerPage();

}  // namespace mrslam::fusion
