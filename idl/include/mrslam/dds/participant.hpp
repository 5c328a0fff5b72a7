#pragma once
// One DDS participant with its publisher, subscriber, topics and endpoints, created from the
// XML profiles and torn down in the right order.

#include <fastdds/dds/domain/DomainParticipant.hpp>
#include <fastdds/dds/publisher/DataWriter.hpp>
#include <fastdds/dds/publisher/Publisher.hpp>
#include <fastdds/dds/subscriber/DataReader.hpp>
#include <fastdds/dds/subscriber/DataReaderListener.hpp>
#include <fastdds/dds/subscriber/Subscriber.hpp>
#include <fastdds/dds/topic/Topic.hpp>
#include <fastdds/dds/topic/TypeSupport.hpp>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>

#include "mrslam/common/dds_settings.hpp"

namespace mrslam::dds {

class DdsError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class Participant {
 public:
  /// Creates the participant from the profiles; throws DdsError with the reason on failure.
  Participant(const DdsSettings& settings, const std::string& name);
  ~Participant();
  Participant(const Participant&) = delete;
  Participant& operator=(const Participant&) = delete;

  template <class PubSubType>
  eprosima::fastdds::dds::DataWriter* createWriter(const std::string& topic_name,
                                                   const std::string& profile) {
    return createWriter(topic_name, eprosima::fastdds::dds::TypeSupport(new PubSubType()), profile);
  }

  template <class PubSubType>
  eprosima::fastdds::dds::DataReader* createReader(
      const std::string& topic_name, const std::string& profile,
      eprosima::fastdds::dds::DataReaderListener* listener) {
    return createReader(topic_name, eprosima::fastdds::dds::TypeSupport(new PubSubType()), profile,
                        listener);
  }

  eprosima::fastdds::dds::DomainParticipant* get() const { return participant_; }
  int domainId() const { return domain_id_; }

 private:
  eprosima::fastdds::dds::DataWriter* createWriter(const std::string& topic_name,
                                                   eprosima::fastdds::dds::TypeSupport type,
                                                   const std::string& profile);
  eprosima::fastdds::dds::DataReader* createReader(
      const std::string& topic_name, eprosima::fastdds::dds::TypeSupport type,
      const std::string& profile, eprosima::fastdds::dds::DataReaderListener* listener);
  eprosima::fastdds::dds::Topic* topic(const std::string& name,
                                       eprosima::fastdds::dds::TypeSupport type);

  /// With DDS Security: logs each remote participant authenticated, and each whose
  /// authentication failed (no credentials, or another CA's), once; counts both at the end.
  class AuthenticationLog;

  int domain_id_ = 0;
  std::unique_ptr<AuthenticationLog> authentication_log_;  ///< outlives participant_
  eprosima::fastdds::dds::DomainParticipant* participant_ = nullptr;
  eprosima::fastdds::dds::Publisher* publisher_ = nullptr;
  eprosima::fastdds::dds::Subscriber* subscriber_ = nullptr;
  std::map<std::string, eprosima::fastdds::dds::Topic*> topics_;
};

/// Waits until `writer` has at least `count` matched readers; false on time-out.
bool waitForReaders(eprosima::fastdds::dds::DataWriter* writer, int count, double timeout_s);

}  // namespace mrslam::dds
