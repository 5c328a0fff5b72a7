#include "mrslam/dds/lossy_link.hpp"

#include <fastdds/rtps/transport/UDPv4TransportDescriptor.h>
#include <fastdds/rtps/transport/shared_mem/SharedMemTransportDescriptor.h>
#include <fastdds/rtps/transport/test_UDPv4TransportDescriptor.h>
#include <fastrtps/xmlparser/XMLProfileManager.h>
#include <atomic>
#include <chrono>
#include <fastdds/dds/domain/DomainParticipant.hpp>
#include <fastdds/dds/domain/DomainParticipantFactory.hpp>
#include <fastdds/dds/publisher/DataWriter.hpp>
#include <fastdds/dds/publisher/Publisher.hpp>
#include <fastdds/dds/subscriber/DataReader.hpp>
#include <fastdds/dds/subscriber/SampleInfo.hpp>
#include <fastdds/dds/subscriber/Subscriber.hpp>
#include <mutex>
#include <random>

#include "mrslam/dds/participant.hpp"
#include "mrslam/dds/topics.hpp"
#include "mrslam_msgsPubSubTypes.h"

namespace mrslam::dds {

namespace {

using namespace eprosima::fastdds::dds;
using eprosima::fastrtps::types::ReturnCode_t;
using Clock = std::chrono::steady_clock;

constexpr std::uint32_t kSharedMemorySegment = 32 * 1024 * 1024;  // as config/dds/profiles.xml

// The sender's drop decisions: seeded, counted.
struct DropDice {
  std::mutex mutex;
  std::mt19937_64 random;
  int percent = 0;
  std::atomic<std::uint64_t> seen{0};
  std::atomic<std::uint64_t> dropped{0};

  bool roll() {
    ++seen;
    std::lock_guard<std::mutex> lock(mutex);
    const bool drop = static_cast<int>(random() % 100) < percent;
    dropped += drop ? 1 : 0;
    return drop;
  }
};

DomainParticipantQos onlyThrough(
    std::shared_ptr<eprosima::fastdds::rtps::TransportDescriptorInterface> transport) {
  DomainParticipantQos qos = PARTICIPANT_QOS_DEFAULT;
  qos.transport().use_builtin_transports = false;
  qos.transport().user_transports.push_back(std::move(transport));
  return qos;
}

bool sameMap(const msg::LocalMap& a, const msg::LocalMap& b) {
  return a.robot_id() == b.robot_id() && a.sequence_number() == b.sequence_number() &&
         a.info().width() == b.info().width() && a.info().height() == b.info().height() &&
         a.info().resolution() == b.info().resolution() && a.data() == b.data();
}

}  // namespace

struct LossyMapLink::Impl {
  std::shared_ptr<DropDice> dice = std::make_shared<DropDice>();
  DomainParticipant* sender = nullptr;
  DomainParticipant* receiver = nullptr;
  DataWriter* writer = nullptr;
  DataReader* reader = nullptr;

  ~Impl() {
    auto* factory = DomainParticipantFactory::get_instance();
    for (DomainParticipant* participant : {sender, receiver}) {
      if (participant != nullptr) {
        participant->delete_contained_entities();
        factory->delete_participant(participant);
      }
    }
  }
};

LossyMapLink::LossyMapLink(const LossyLinkSettings& settings) : impl_(std::make_unique<Impl>()) {
  auto* factory = DomainParticipantFactory::get_instance();
  if (factory->load_XML_profiles_file(settings.profiles_file) != ReturnCode_t::RETCODE_OK) {
    throw DdsError(settings.profiles_file + ": Fast DDS could not load the XML profiles");
  }
  // After the profiles (which may set library settings): every sample goes through the network.
  eprosima::fastrtps::LibrarySettingsAttributes library;
  library.intraprocess_delivery = eprosima::fastrtps::INTRAPROCESS_OFF;
  eprosima::fastrtps::xmlparser::XMLProfileManager::library_settings(library);
  impl_->dice->random.seed(settings.seed);
  impl_->dice->percent = settings.drop_data_frag_percent;
  auto lossy = std::make_shared<eprosima::fastdds::rtps::test_UDPv4TransportDescriptor>();
  std::weak_ptr<DropDice> dice = impl_->dice;
  lossy->drop_data_frag_messages_filter_ = [dice](eprosima::fastrtps::rtps::CDRMessage_t&) {
    const auto shared = dice.lock();
    return shared && shared->roll();
  };
  if (settings.transport == LinkTransport::kUdp) {
    impl_->sender = factory->create_participant(settings.domain_id, onlyThrough(lossy));
    impl_->receiver = factory->create_participant(
        settings.domain_id,
        onlyThrough(std::make_shared<eprosima::fastdds::rtps::UDPv4TransportDescriptor>()));
  } else {
    for (DomainParticipant** participant : {&impl_->sender, &impl_->receiver}) {
      auto shm = std::make_shared<eprosima::fastdds::rtps::SharedMemTransportDescriptor>();
      shm->segment_size(kSharedMemorySegment);
      *participant = factory->create_participant(settings.domain_id, onlyThrough(shm));
    }
  }
  if (impl_->sender == nullptr || impl_->receiver == nullptr) {
    throw DdsError("lossy link: cannot create the participants");
  }
  TypeSupport type(new msg::LocalMapPubSubType());
  type.register_type(impl_->sender);
  type.register_type(impl_->receiver);
  Topic* sent =
      impl_->sender->create_topic(kLocalMapTopic, type.get_type_name(), TOPIC_QOS_DEFAULT);
  Topic* received =
      impl_->receiver->create_topic(kLocalMapTopic, type.get_type_name(), TOPIC_QOS_DEFAULT);
  Publisher* publisher = impl_->sender->create_publisher(PUBLISHER_QOS_DEFAULT);
  Subscriber* subscriber = impl_->receiver->create_subscriber(SUBSCRIBER_QOS_DEFAULT);
  if (sent == nullptr || received == nullptr || publisher == nullptr || subscriber == nullptr) {
    throw DdsError("lossy link: cannot create the topics");
  }
  impl_->writer = publisher->create_datawriter_with_profile(sent, kMapWriterProfile);
  impl_->reader = subscriber->create_datareader_with_profile(received, kMapReaderProfile);
  if (impl_->writer == nullptr || impl_->reader == nullptr) {
    throw DdsError("lossy link: cannot create the map writer and reader from the profiles");
  }
  if (!waitForReaders(impl_->writer, 1, settings.match_timeout_s)) {
    throw DdsError("lossy link: the map reader did not match");
  }
}

LossyMapLink::~LossyMapLink() = default;

MapDelivery LossyMapLink::send(const msg::LocalMap& map, double timeout_s) {
  MapDelivery delivery;
  const Clock::time_point written = Clock::now();
  const Clock::time_point deadline = written + std::chrono::duration_cast<Clock::duration>(
                                                   std::chrono::duration<double>(timeout_s));
  msg::LocalMap copy = map;
  if (!impl_->writer->write(&copy)) {
    return delivery;
  }
  msg::LocalMap taken;
  SampleInfo info;
  while (Clock::now() < deadline) {
    if (!impl_->reader->wait_for_unread_message({0, 50'000'000})) {
      continue;
    }
    while (impl_->reader->take_next_sample(&taken, &info) == ReturnCode_t::RETCODE_OK) {
      if (info.valid_data && taken.sequence_number() == map.sequence_number()) {
        delivery.arrived = true;
        delivery.whole = sameMap(taken, map);
        delivery.delay_ms =
            std::chrono::duration<double, std::milli>(Clock::now() - written).count();
        return delivery;
      }
    }
  }
  return delivery;
}

LossyLinkCounters LossyMapLink::counters() const {
  return {impl_->dice->seen.load(), impl_->dice->dropped.load()};
}

}  // namespace mrslam::dds
