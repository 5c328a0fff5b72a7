#include "mrslam/dds/participant.hpp"

#include <spdlog/spdlog.h>

#include <fastdds/rtps/attributes/ServerAttributes.h>
#include <fastrtps/utils/IPLocator.h>
#include <chrono>
#include <fastdds/dds/domain/DomainParticipantFactory.hpp>
#include <fastdds/dds/domain/DomainParticipantListener.hpp>
#include <fastdds/dds/domain/qos/DomainParticipantQos.hpp>
#include <fastdds/dds/publisher/qos/PublisherQos.hpp>
#include <fastdds/dds/subscriber/qos/SubscriberQos.hpp>
#include <fastdds/dds/topic/qos/TopicQos.hpp>
#include <filesystem>
#include <mutex>
#include <set>
#include <sstream>
#include <thread>

namespace mrslam::dds {

using eprosima::fastdds::dds::DomainParticipantFactory;
using eprosima::fastrtps::types::ReturnCode_t;

namespace {

// Fast DDS keeps loaded profiles for the whole process: load each file once.
void loadProfilesOnce(const std::string& path) {
  static std::mutex mutex;
  static std::set<std::string> loaded;
  std::lock_guard<std::mutex> lock(mutex);
  const std::string key = std::filesystem::weakly_canonical(path).string();
  if (loaded.count(key) != 0) {
    return;
  }
  if (!std::filesystem::exists(path)) {
    throw DdsError(path + ": DDS profiles file not found");
  }
  if (DomainParticipantFactory::get_instance()->load_XML_profiles_file(path) !=
      ReturnCode_t::RETCODE_OK) {
    throw DdsError(path + ": Fast DDS could not load the XML profiles");
  }
  loaded.insert(key);
}

// The participant as a client of the Discovery Server at `address` (IPv4:port) with id `id`.
void makeDiscoveryClient(eprosima::fastdds::dds::DomainParticipantQos& qos,
                         const std::string& address, int id) {
  namespace rtps = eprosima::fastrtps::rtps;
  const std::string problem = checkDiscoveryServerAddress(address);
  if (!problem.empty()) {
    throw DdsError("discovery server: " + problem);
  }
  const std::size_t colon = address.rfind(':');
  rtps::Locator_t locator;
  rtps::IPLocator::setIPv4(locator, address.substr(0, colon));
  locator.port = static_cast<std::uint32_t>(std::stoi(address.substr(colon + 1)));
  rtps::RemoteServerAttributes server;
  server.metatrafficUnicastLocatorList.push_back(locator);
  if (!eprosima::fastdds::rtps::get_server_client_default_guidPrefix(id, server.guidPrefix)) {
    throw DdsError("discovery server: no GUID prefix for server id " + std::to_string(id));
  }
  auto& discovery = qos.wire_protocol().builtin.discovery_config;
  discovery.discoveryProtocol = rtps::DiscoveryProtocol_t::CLIENT;
  discovery.m_DiscoveryServers.push_back(server);
}

// DDS Security with the builtin plugins and the files of scripts/make_test_pki.sh.
void makeSecure(eprosima::fastdds::dds::DomainParticipantQos& qos, const DdsSettings& settings) {
  if (settings.security_identity.empty()) {
    throw DdsError("security: no identity to prove (dds.security.identity)");
  }
  const std::vector<std::string> files = securityFiles(settings);
  for (const std::string& file : files) {
    if (!std::filesystem::exists(file)) {
      throw DdsError("security: " + file + " not found (scripts/make_test_pki.sh makes it)");
    }
  }
  const auto uri = [](const std::string& file) {
    return "file://" + std::filesystem::absolute(file).string();
  };
  auto& properties = qos.properties().properties();
  const std::string auth = "dds.sec.auth.builtin.PKI-DH.";
  const std::string access = "dds.sec.access.builtin.Access-Permissions.";
  properties.emplace_back("dds.sec.auth.plugin", "builtin.PKI-DH");
  properties.emplace_back(auth + "identity_ca", uri(files[0]));
  properties.emplace_back(auth + "identity_certificate", uri(files[2]));
  properties.emplace_back(auth + "private_key", uri(files[3]));
  properties.emplace_back("dds.sec.access.plugin", "builtin.Access-Permissions");
  properties.emplace_back(access + "permissions_ca", uri(files[0]));
  properties.emplace_back(access + "governance", uri(files[1]));
  properties.emplace_back(access + "permissions", uri(files[4]));
  properties.emplace_back("dds.sec.crypto.plugin", "builtin.AES-GCM-GMAC");
}

}  // namespace

/// DDS Security's verdict on each remote participant, logged once per participant and counted:
/// a robot whose credentials are refused is named in the log, not merely missing from the map.
class Participant::AuthenticationLog : public eprosima::fastdds::dds::DomainParticipantListener {
 public:
  explicit AuthenticationLog(std::string name) : name_(std::move(name)) {}

  void onParticipantAuthentication(
      eprosima::fastdds::dds::DomainParticipant* /*participant*/,
      eprosima::fastrtps::rtps::ParticipantAuthenticationInfo&& info) override {
    using Info = eprosima::fastrtps::rtps::ParticipantAuthenticationInfo;
    std::ostringstream guid;
    guid << info.guid.guidPrefix;
    const bool authorized = info.status == Info::AUTHORIZED_PARTICIPANT;
    std::lock_guard<std::mutex> lock(mutex_);
    std::set<std::string>& seen = authorized ? authenticated_ : refused_;
    if (!seen.insert(guid.str()).second) {
      return;  // a handshake retried: logged already
    }
    if (authorized) {
      spdlog::info("{}: DDS Security: participant {} authenticated", name_, guid.str());
    } else {
      spdlog::warn(
          "{}: DDS Security: participant {} failed authentication (no credentials, or another "
          "CA's); nothing of it is read",
          name_, guid.str());
    }
  }

  /// One line of the counts, when the participant is done.
  void summarize() const {
    spdlog::info("{}: DDS Security: {} participant(s) authenticated, {} refused", name_,
                 authenticated(), refused());
  }

  int authenticated() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return static_cast<int>(authenticated_.size());
  }
  int refused() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return static_cast<int>(refused_.size());
  }

 private:
  std::string name_;
  mutable std::mutex mutex_;
  std::set<std::string> authenticated_;  ///< GUID prefixes
  std::set<std::string> refused_;
};

Participant::Participant(const DdsSettings& settings, const std::string& name)
    : domain_id_(settings.domain_id) {
  loadProfilesOnce(settings.profiles_file);
  auto* factory = DomainParticipantFactory::get_instance();
  eprosima::fastdds::dds::DomainParticipantQos qos;
  if (factory->get_participant_qos_from_profile(settings.participant_profile, qos) !=
      ReturnCode_t::RETCODE_OK) {
    throw DdsError("no participant profile '" + settings.participant_profile + "' in " +
                   settings.profiles_file);
  }
  if (!settings.discovery_server.empty()) {
    makeDiscoveryClient(qos, settings.discovery_server, settings.discovery_server_id);
    spdlog::info("{}: discovery through the server at {} (id {})", name, settings.discovery_server,
                 settings.discovery_server_id);
  }
  if (!settings.security_dir.empty()) {
    makeSecure(qos, settings);
    spdlog::info("{}: DDS Security as '{}' ({})", name, settings.security_identity,
                 settings.security_dir);
  }
  if (!settings.security_dir.empty()) {
    authentication_log_ = std::make_unique<AuthenticationLog>(name);
  }
  // The listener hears only the authentications: no status of the endpoints (their own
  // listeners take those).
  participant_ = factory->create_participant(settings.domain_id, qos, authentication_log_.get(),
                                             eprosima::fastdds::dds::StatusMask::none());
  if (participant_ == nullptr) {
    throw DdsError("cannot create DDS participant '" + name + "' on domain " +
                   std::to_string(settings.domain_id) + " with profile '" +
                   settings.participant_profile + "' of " + settings.profiles_file);
  }
  publisher_ = participant_->create_publisher(eprosima::fastdds::dds::PUBLISHER_QOS_DEFAULT);
  subscriber_ = participant_->create_subscriber(eprosima::fastdds::dds::SUBSCRIBER_QOS_DEFAULT);
  if (publisher_ == nullptr || subscriber_ == nullptr) {
    throw DdsError("cannot create the DDS publisher/subscriber of '" + name + "'");
  }
}

Participant::~Participant() {
  if (participant_ != nullptr) {
    participant_->delete_contained_entities();
    DomainParticipantFactory::get_instance()->delete_participant(participant_);
  }
  if (authentication_log_) {
    authentication_log_->summarize();
  }
}

eprosima::fastdds::dds::Topic* Participant::topic(const std::string& name,
                                                  eprosima::fastdds::dds::TypeSupport type) {
  const auto found = topics_.find(name);
  if (found != topics_.end()) {
    return found->second;
  }
  if (type.register_type(participant_) != ReturnCode_t::RETCODE_OK) {
    throw DdsError("cannot register DDS type " + type.get_type_name());
  }
  auto* created = participant_->create_topic(name, type.get_type_name(),
                                             eprosima::fastdds::dds::TOPIC_QOS_DEFAULT);
  if (created == nullptr) {
    throw DdsError("cannot create DDS topic " + name);
  }
  topics_[name] = created;
  return created;
}

eprosima::fastdds::dds::DataWriter* Participant::createWriter(
    const std::string& topic_name, eprosima::fastdds::dds::TypeSupport type,
    const std::string& profile) {
  auto* writer = publisher_->create_datawriter_with_profile(topic(topic_name, type), profile);
  if (writer == nullptr) {
    throw DdsError("cannot create a DDS writer on " + topic_name + " with profile " + profile);
  }
  return writer;
}

eprosima::fastdds::dds::DataReader* Participant::createReader(
    const std::string& topic_name, eprosima::fastdds::dds::TypeSupport type,
    const std::string& profile, eprosima::fastdds::dds::DataReaderListener* listener) {
  auto* reader =
      subscriber_->create_datareader_with_profile(topic(topic_name, type), profile, listener);
  if (reader == nullptr) {
    throw DdsError("cannot create a DDS reader on " + topic_name + " with profile " + profile);
  }
  return reader;
}

bool waitForReaders(eprosima::fastdds::dds::DataWriter* writer, int count, double timeout_s) {
  const auto deadline = std::chrono::steady_clock::now() +
                        std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                            std::chrono::duration<double>(timeout_s));
  while (true) {
    eprosima::fastdds::dds::PublicationMatchedStatus status;
    writer->get_publication_matched_status(status);
    if (status.current_count >= count) {
      return true;
    }
    if (std::chrono::steady_clock::now() >= deadline) {
      return false;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
}

}  // namespace mrslam::dds
