// fusion_agent: subscribes to every robot's local map, composes the global map, publishes it on
// DDS and writes it to files.

#include <spdlog/spdlog.h>

#include <CLI/CLI.hpp>
#include <chrono>
#include <thread>

#include "fusion_loop.hpp"
#include "mrslam/common/dds_settings.hpp"
#include "mrslam/common/heap.hpp"
#include "mrslam/common/logging.hpp"
#include "mrslam/common/shutdown.hpp"
#include "mrslam/common/version.hpp"

int main(int argc, char** argv) {
  mrslam::logToStandardError("fusion_agent");
  CLI::App app{"mrslam fusion agent: merges the robots' maps into one global map"};
  std::string config_path;
  int domain = -1;
  std::string out;
  double max_runtime = -1.0;
  std::string discovery_server;
  std::string security_dir;
  std::string security_identity;
  std::string log_level = "info";
  int viewer_port = -1;
  app.add_option("--config", config_path, "fusion config YAML")->required();
  app.add_option("--domain", domain, "DDS domain id (overrides the config)")
      ->check(CLI::Range(0, 232));
  app.add_option("--out", out, "output folder (overrides the config)");
  app.add_option("--discovery-server", discovery_server,
                 "IPv4:port of a Discovery Server to discover through (overrides the config)")
      ->check(
          [](const std::string& address) { return mrslam::checkDiscoveryServerAddress(address); });
  app.add_option("--security-dir", security_dir,
                 "DDS Security from this folder's files (scripts/make_test_pki.sh)");
  app.add_option("--security-identity", security_identity,
                 "the identity to prove (default: the config's, else \"fusion\")");
  app.add_option("--max-runtime", max_runtime, "give up after this many seconds (0: never)");
  app.add_option("--viewer-port", viewer_port,
                 "serve the live viewer on this local HTTP port (0: any free port)")
      ->check(CLI::Range(0, 65535));
  app.add_option("--log-level", log_level, "trace, debug, info, warn, error");
  app.set_version_flag("--version", mrslam::versionLine("fusion_agent"));
  CLI11_PARSE(app, argc, argv);
  spdlog::set_level(spdlog::level::from_str(log_level));
  if (!mrslam::retainHeapForReuse()) {  // every merge reuses the last one's memory
    spdlog::debug("fusion_agent: the C library keeps its own heap settings");
  }
  try {
    mrslam::fusion::FusionConfig config = mrslam::fusion::loadFusionConfig(config_path);
    if (domain >= 0) {
      config.dds.domain_id = domain;
    }
    if (!out.empty()) {
      config.output_folder = out;
    }
    if (!discovery_server.empty()) {
      config.dds.discovery_server = discovery_server;
    }
    if (!security_dir.empty()) {
      config.dds.security_dir = security_dir;
    }
    if (!security_identity.empty()) {
      config.dds.security_identity = security_identity;
    } else if (config.dds.security_identity.empty()) {
      config.dds.security_identity = "fusion";
    }
    if (viewer_port >= 0) {
      config.viewer.enabled = true;
      config.viewer.port = viewer_port;
    }
    if (max_runtime >= 0.0) {
      config.max_runtime_s = max_runtime;
    }
    mrslam::fusion::FusionLoop loop(config);
    return loop.run(mrslam::shutdownRequested());
  } catch (const std::exception& error) {
    spdlog::error("fusion_agent: {}", error.what());
    return 1;
  }
}
