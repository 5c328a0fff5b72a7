// Maps over a network that loses a fifth of the DATA_FRAG messages (Fast DDS's test UDP
// transport; UDP only, intraprocess delivery off): every map still arrives whole.

#include "mrslam/dds/lossy_link.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <random>

#include "test_data.hpp"
#include "test_domain.hpp"

namespace mrslam::dds {
namespace {

msg::LocalMap randomMap(std::uint64_t sequence, std::mt19937& random) {
  msg::LocalMap map;
  map.robot_id("robot1");
  map.sequence_number(sequence);
  map.info().resolution(0.05);
  map.info().width(800);
  map.info().height(800);
  std::vector<std::uint8_t> cells(800 * 800);
  for (std::uint8_t& cell : cells) {
    cell = static_cast<std::uint8_t>(random() % 102) - 1;  // -1 (0xFF) .. 100
  }
  map.data(std::move(cells));
  return map;
}

TEST(LossyLinkTest, MapsArriveWholeWhenAFifthOfTheFragmentsIsLost) {
  LossyLinkSettings settings;
  settings.domain_id = test::testDomain();
  settings.profiles_file = test::sourcePath("config/dds/profiles.xml");
  settings.drop_data_frag_percent = 20;
  LossyMapLink link(settings);
  std::mt19937 random(7);
  std::vector<double> delays_ms;
  for (std::uint64_t sequence = 1; sequence <= 5; ++sequence) {
    const MapDelivery delivery = link.send(randomMap(sequence, random), 60.0);
    EXPECT_TRUE(delivery.arrived) << "map " << sequence;
    EXPECT_TRUE(delivery.whole) << "map " << sequence;
    delays_ms.push_back(delivery.delay_ms);
  }
  const LossyLinkCounters counters = link.counters();
  // 640 kB maps travel in fragments: some were lost, and recovered.
  EXPECT_GT(counters.data_frags_sent, 50u);
  EXPECT_GT(counters.data_frags_dropped, 0u);
  const double share = static_cast<double>(counters.data_frags_dropped) /
                       static_cast<double>(counters.data_frags_sent);
  EXPECT_GT(share, 0.05);
  EXPECT_LT(share, 0.4);
  std::sort(delays_ms.begin(), delays_ms.end());
  std::printf(
      "5 maps of 800 x 800 cells: %llu of %llu DATA_FRAG messages dropped; delay median "
      "%.0f ms, max %.0f ms\n",
      static_cast<unsigned long long>(counters.data_frags_dropped),
      static_cast<unsigned long long>(counters.data_frags_sent), delays_ms[2], delays_ms.back());
}

}  // namespace
}  // namespace mrslam::dds
