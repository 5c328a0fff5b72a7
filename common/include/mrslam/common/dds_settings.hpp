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
};

/// Reads the `dds:` section. profiles_file defaults to dds/profiles.xml beside the config file.
DdsSettings loadDdsSettings(const Config& section);

}  // namespace mrslam
