#pragma once
// Topic names and the QoS profile (config/dds/profiles.xml) each endpoint uses.

namespace mrslam::dds {

inline constexpr const char* kRobotPoseTopic = "mrslam/robot_pose";
inline constexpr const char* kLocalMapTopic = "mrslam/local_map";
inline constexpr const char* kRobotStatusTopic = "mrslam/robot_status";
inline constexpr const char* kTransformsTopic = "mrslam/transforms";
inline constexpr const char* kGlobalMapTopic = "mrslam/global_map";
inline constexpr const char* kFusionStatusTopic = "mrslam/fusion_status";
inline constexpr const char* kRendezvousTopic = "mrslam/rendezvous";

inline constexpr const char* kPoseWriterProfile = "mrslam_pose_writer";
inline constexpr const char* kPoseReaderProfile = "mrslam_pose_reader";
inline constexpr const char* kMapWriterProfile = "mrslam_map_writer";
inline constexpr const char* kMapReaderProfile = "mrslam_map_reader";
inline constexpr const char* kStateWriterProfile = "mrslam_state_writer";
inline constexpr const char* kStateReaderProfile = "mrslam_state_reader";
inline constexpr const char* kSightingWriterProfile = "mrslam_sighting_writer";
inline constexpr const char* kSightingReaderProfile = "mrslam_sighting_reader";
inline constexpr const char* kRosPoseWriterProfile = "mrslam_ros_pose_writer";
inline constexpr const char* kRosPoseReaderProfile = "mrslam_ros_pose_reader";

}  // namespace mrslam::dds
