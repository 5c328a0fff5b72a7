#pragma once
// The `dds:` section of an agent's config: which domain and which Fast DDS profiles. A plain
// struct, so configs load without any DDS library.

#include <string>
#include <vector>

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
  /// DDS Security (PKI-DH, Access-Permissions, AES-GCM-GMAC) from the files of
  /// scripts/make_test_pki.sh in this folder; empty: off. The participant proves itself with
  /// `security_identity`.cert.pem / .key.pem / .permissions.smime, trusts ca.cert.pem and
  /// follows governance.smime.
  std::string security_dir;
  std::string security_identity;  ///< empty: the agent's own (robot id, or "fusion")
};

/// The fusion agent's default participant profile: UDP alone. Fast DDS 2.9's shared memory may
/// never deliver to a subscriber restarted after a crash on the robots' host, which reuses the
/// dead process's port (eProsima/Fast-DDS#5053); the robots' maps reach it over UDP loopback
/// as fast (docs/architecture.md).
constexpr const char* kFusionParticipantProfile = "mrslam_participant_udp";

/// Reads the `dds:` section. profiles_file defaults to dds/profiles.xml beside the config file,
/// participant_profile to `default_profile`.
DdsSettings loadDdsSettings(const Config& section,
                            const std::string& default_profile = "mrslam_participant");

/// The files security needs, in the order CA, governance, certificate, key, permissions.
std::vector<std::string> securityFiles(const DdsSettings& settings);

/// Empty when `address` is `IPv4:port` (port 1-65535), else what is wrong with it.
std::string checkDiscoveryServerAddress(const std::string& address);

}  // namespace mrslam
