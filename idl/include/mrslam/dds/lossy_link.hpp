#pragma once
// A map link that loses packets, for tests and benchmarks of reliable delivery: two
// participants in one process, joined by UDP only (no shared memory, intraprocess delivery off
// for the whole process), the sender on Fast DDS's test UDP transport, which drops a seeded share
// of the DATA_FRAG messages it sends. Or joined by shared memory only, to measure that path. The
// map endpoints use the agents' XML profiles, so what is measured is how the agents' maps survive a
// lossy network.

#include <cstdint>
#include <memory>
#include <string>

#include "mrslam_msgs.h"

namespace mrslam::dds {

/// How the two participants are joined.
enum class LinkTransport {
  kUdp,           ///< UDPv4 on the loopback, the sender on the lossy test transport
  kSharedMemory,  ///< shared memory only (the agents' 32 MB segment); nothing is dropped
};

struct LossyLinkSettings {
  int domain_id = 0;
  LinkTransport transport = LinkTransport::kUdp;
  std::string profiles_file;        ///< the agents' profiles (map writer / reader QoS)
  int drop_data_frag_percent = 20;  ///< DATA_FRAG messages the sender drops (0-100)
  std::uint64_t seed = 1;           ///< seed of the drops
  double match_timeout_s = 10.0;    ///< writer and reader must match within this
};

/// One map's delivery.
struct MapDelivery {
  bool arrived = false;   ///< the reader took a sample of this sequence number in time
  bool whole = false;     ///< ... and its cells and header equal what was sent
  double delay_ms = 0.0;  ///< write() → take()
};

struct LossyLinkCounters {
  std::uint64_t data_frags_sent = 0;     ///< DATA_FRAG messages the sender's transport saw
  std::uint64_t data_frags_dropped = 0;  ///< of which dropped
};

class LossyMapLink {
 public:
  /// Creates both participants and the map writer and reader; throws DdsError when they cannot
  /// be created or do not match in time. Call before any other participant of the process.
  explicit LossyMapLink(const LossyLinkSettings& settings);
  ~LossyMapLink();
  LossyMapLink(const LossyMapLink&) = delete;
  LossyMapLink& operator=(const LossyMapLink&) = delete;

  /// Writes `map` and waits up to `timeout_s` for the reader to take it.
  MapDelivery send(const msg::LocalMap& map, double timeout_s);
  LossyLinkCounters counters() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace mrslam::dds
