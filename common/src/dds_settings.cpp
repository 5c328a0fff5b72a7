#include "mrslam/common/dds_settings.hpp"

#include <arpa/inet.h>

#include <filesystem>

namespace mrslam {

DdsSettings loadDdsSettings(const Config& section, const std::string& default_profile) {
  DdsSettings settings;
  settings.domain_id = static_cast<int>(section.getInt("domain_id", 0, {0, 232}));
  const std::string beside_config =
      (std::filesystem::path(section.folder()) / "dds" / "profiles.xml")
          .lexically_normal()
          .string();
  settings.profiles_file = section.getPath("profiles_file", beside_config);
  settings.participant_profile = section.getString("participant_profile", default_profile);
  settings.discovery_server = section.getString("discovery_server", "");
  if (!settings.discovery_server.empty()) {
    const std::string problem = checkDiscoveryServerAddress(settings.discovery_server);
    if (!problem.empty()) {
      section.fail("discovery_server", problem);
    }
  }
  settings.discovery_server_id =
      static_cast<int>(section.getInt("discovery_server_id", 0, {0, 255}));
  const Config security = section.section("security");
  settings.security_dir = security.getPath("dir", "");
  settings.security_identity = security.getString("identity", "");
  return settings;
}

std::vector<std::string> securityFiles(const DdsSettings& settings) {
  const std::filesystem::path dir(settings.security_dir);
  const std::string& id = settings.security_identity;
  return {(dir / "ca.cert.pem").string(), (dir / "governance.smime").string(),
          (dir / (id + ".cert.pem")).string(), (dir / (id + ".key.pem")).string(),
          (dir / (id + ".permissions.smime")).string()};
}

std::string checkDiscoveryServerAddress(const std::string& address) {
  const std::size_t colon = address.rfind(':');
  if (colon == std::string::npos) {
    return "'" + address + "' is not IPv4:port";
  }
  in_addr ip{};
  if (::inet_pton(AF_INET, address.substr(0, colon).c_str(), &ip) != 1) {
    return "'" + address.substr(0, colon) + "' is not an IPv4 address";
  }
  const std::string port = address.substr(colon + 1);
  const bool digits = !port.empty() && port.size() <= 5 &&
                      port.find_first_not_of("0123456789") == std::string::npos;
  if (!digits || std::stoi(port) < 1 || std::stoi(port) > 65535) {
    return "'" + port + "' is not a port (1-65535)";
  }
  return "";
}

}  // namespace mrslam
