#include "mrslam/common/dds_settings.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace mrslam {
namespace {

using ::testing::HasSubstr;

std::string loadError(const std::string& text) {
  try {
    loadDdsSettings(Config::loadString(text, "/etc/mrslam/agent.yaml"));
  } catch (const ConfigError& error) {
    return error.what();
  }
  return "no error";
}

TEST(DdsSettingsTest, DefaultsAreSimpleDiscoveryWithTheProfilesBesideTheConfig) {
  const DdsSettings settings =
      loadDdsSettings(Config::loadString("domain_id: 7\n", "/etc/mrslam/agent.yaml"));
  EXPECT_EQ(settings.domain_id, 7);
  EXPECT_EQ(settings.profiles_file, "/etc/mrslam/dds/profiles.xml");
  EXPECT_EQ(settings.participant_profile, "mrslam_participant");
  EXPECT_TRUE(settings.discovery_server.empty());
  EXPECT_EQ(settings.discovery_server_id, 0);
}

TEST(DdsSettingsTest, ADiscoveryServerIsAnIpv4AddressAndPort) {
  const DdsSettings settings = loadDdsSettings(Config::loadString(
      "discovery_server: 192.168.1.20:11811\ndiscovery_server_id: 3\n", "a.yaml"));
  EXPECT_EQ(settings.discovery_server, "192.168.1.20:11811");
  EXPECT_EQ(settings.discovery_server_id, 3);
  EXPECT_THAT(loadError("discovery_server: robots.local:11811\n"),
              HasSubstr("agent.yaml:1: discovery_server: 'robots.local' is not an IPv4 address"));
  EXPECT_THAT(loadError("discovery_server: 10.0.0.1\n"), HasSubstr("is not IPv4:port"));
  EXPECT_THAT(loadError("discovery_server: 10.0.0.1:70000\n"),
              HasSubstr("'70000' is not a port (1-65535)"));
  EXPECT_THAT(loadError("discovery_server: \"10.0.0.1:\"\n"), HasSubstr("is not a port"));
  EXPECT_THAT(loadError("discovery_server_id: 256\n"), HasSubstr("discovery_server_id"));
  EXPECT_EQ(checkDiscoveryServerAddress("127.0.0.1:1"), "");
  EXPECT_NE(checkDiscoveryServerAddress("127.0.0.1:0"), "");
}

TEST(DdsSettingsTest, SecurityNamesTheCredentialsFolderAndIdentity) {
  const DdsSettings settings = loadDdsSettings(Config::loadString(
      "security:\n  dir: ../pki\n  identity: robot7\n", "/etc/mrslam/agent.yaml"));
  EXPECT_EQ(settings.security_dir, "/etc/pki");
  EXPECT_EQ(settings.security_identity, "robot7");
  const std::vector<std::string> files = securityFiles(settings);
  ASSERT_EQ(files.size(), 5u);
  EXPECT_EQ(files[0], "/etc/pki/ca.cert.pem");
  EXPECT_EQ(files[1], "/etc/pki/governance.smime");
  EXPECT_EQ(files[2], "/etc/pki/robot7.cert.pem");
  EXPECT_EQ(files[3], "/etc/pki/robot7.key.pem");
  EXPECT_EQ(files[4], "/etc/pki/robot7.permissions.smime");
  EXPECT_TRUE(loadDdsSettings(Config::loadString("domain_id: 1\n", "a.yaml")).security_dir.empty());
}

}  // namespace
}  // namespace mrslam
