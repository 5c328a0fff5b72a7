#include "mrslam/common/dds_settings.hpp"

#include <filesystem>

namespace mrslam {

DdsSettings loadDdsSettings(const Config& section) {
  DdsSettings settings;
  settings.domain_id = static_cast<int>(section.getInt("domain_id", 0, {0, 232}));
  const std::string beside_config =
      (std::filesystem::path(section.folder()) / "dds" / "profiles.xml")
          .lexically_normal()
          .string();
  settings.profiles_file = section.getPath("profiles_file", beside_config);
  settings.participant_profile =
      section.getString("participant_profile", settings.participant_profile);
  return settings;
}

}  // namespace mrslam
