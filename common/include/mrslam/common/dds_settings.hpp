#pragma once
// The `dds:` section of an agent's config: which domain and which Fast DDS profiles. A plain
// struct, so configs load without any DDS library.

#include <string>

#include "mrslam/common/config.hpp"

namespace mrslam {

struct DdsSettings {
  int domain_id = 0;          ///< DDS domain of the team (0..232)
  std::string profiles_file;  ///< Fast DDS XML profiles: transports and QoS
  std::string participant_profile = "mrslam_participant";  ///< participant profile to use
  /// Discovery Server mode: `IPv4:port` of the server (`fastdds discovery -i ID -l IP -p PORT`),
  /// the participant being its client; empty: simple discovery (multicast).
  std::string discovery_server;
  int discovery_server_id = 0;  ///< the server's id (-i), which fixes its GUID prefix
};

/// Reads the `dds:` section. profiles_file defaults to dds/profiles.xml beside the config file.
DdsSettings loadDdsSettings(const Config& section);

/// Empty when `address` is `IPv4:port` (port 1-65535), else what is wrong with it.
std::string checkDiscoveryServerAddress(const std::string& address);

}  // namespace mrslam
