// The XML profiles give every endpoint the QoS the design asks for.

#include "mrslam/dds/participant.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <fastdds/rtps/transport/shared_mem/SharedMemTransportDescriptor.h>

#include "mrslam/dds/topics.hpp"
#include "mrslam_msgsPubSubTypes.h"
#include "test_data.hpp"
#include "test_domain.hpp"

namespace mrslam::dds {
namespace {

using namespace eprosima::fastdds::dds;

DdsSettings testSettings() {
  DdsSettings settings;
  settings.domain_id = test::testDomain();
  settings.profiles_file = test::sourcePath("config/dds/profiles.xml");
  return settings;
}

TEST(ParticipantTest, MapEndpointsAreReliableTransientLocalKeepLastOne) {
  Participant participant(testSettings(), "qos test");
  DataWriter* writer =
      participant.createWriter<msg::LocalMapPubSubType>(kLocalMapTopic, kMapWriterProfile);
  DataReader* reader =
      participant.createReader<msg::LocalMapPubSubType>(kLocalMapTopic, kMapReaderProfile, nullptr);
  const DataWriterQos writer_qos = writer->get_qos();
  EXPECT_EQ(writer_qos.reliability().kind, RELIABLE_RELIABILITY_QOS);
  EXPECT_EQ(writer_qos.durability().kind, TRANSIENT_LOCAL_DURABILITY_QOS);
  EXPECT_EQ(writer_qos.history().kind, KEEP_LAST_HISTORY_QOS);
  EXPECT_EQ(writer_qos.history().depth, 1);
  EXPECT_EQ(writer_qos.resource_limits().max_instances, 256);
  EXPECT_EQ(writer_qos.endpoint().history_memory_policy,
            eprosima::fastrtps::rtps::PREALLOCATED_WITH_REALLOC_MEMORY_MODE);
  EXPECT_EQ(writer_qos.publish_mode().kind, ASYNCHRONOUS_PUBLISH_MODE);
  const DataReaderQos reader_qos = reader->get_qos();
  EXPECT_EQ(reader_qos.reliability().kind, RELIABLE_RELIABILITY_QOS);
  EXPECT_EQ(reader_qos.durability().kind, TRANSIENT_LOCAL_DURABILITY_QOS);
  EXPECT_EQ(reader_qos.resource_limits().max_instances, 256);
}

TEST(ParticipantTest, PoseEndpointsAreBestEffort) {
  Participant participant(testSettings(), "qos test");
  DataWriter* writer =
      participant.createWriter<msg::RobotPosePubSubType>(kRobotPoseTopic, kPoseWriterProfile);
  EXPECT_EQ(writer->get_qos().reliability().kind, BEST_EFFORT_RELIABILITY_QOS);
  EXPECT_EQ(writer->get_qos().durability().kind, VOLATILE_DURABILITY_QOS);
}

TEST(ParticipantTest, ParticipantUsesTheLargeSharedMemorySegment) {
  Participant participant(testSettings(), "qos test");
  const DomainParticipantQos qos = participant.get()->get_qos();
  EXPECT_FALSE(qos.transport().use_builtin_transports);
  ASSERT_EQ(qos.transport().user_transports.size(), 2u);
  bool found_shm = false;
  for (const auto& transport : qos.transport().user_transports) {
    if (const auto* shm =
            dynamic_cast<const eprosima::fastdds::rtps::SharedMemTransportDescriptor*>(
                transport.get())) {
      found_shm = true;
      EXPECT_GE(shm->segment_size(), 16u * 1024u * 1024u);
    }
  }
  EXPECT_TRUE(found_shm);
}

TEST(ParticipantTest, MissingProfilesFileIsAClearError) {
  DdsSettings settings = testSettings();
  settings.profiles_file = "/nonexistent/profiles.xml";
  try {
    Participant participant(settings, "bad");
    FAIL() << "no error";
  } catch (const DdsError& error) {
    EXPECT_STREQ(error.what(), "/nonexistent/profiles.xml: DDS profiles file not found");
  }
}

TEST(ParticipantTest, UnknownParticipantProfileIsAClearError) {
  DdsSettings settings = testSettings();
  settings.participant_profile = "no_such_profile";
  EXPECT_THROW(Participant(settings, "bad"), DdsError);
}

}  // namespace
}  // namespace mrslam::dds
