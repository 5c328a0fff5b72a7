#pragma once
// The protocol side of an emulated Hokuyo ranger: request lines in, SCIP 2.0 reply text out,
// and the replies of an MD/MS scan stream. Pure: no I/O and no clock (times are given); the
// HokuyoEmulator adds the pseudo-terminal, the timing and the faults.

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "mrslam/drivers/scip_geometry.hpp"
#include "mrslam/drivers/scip_protocol.hpp"

namespace mrslam::drivers {

/// What an emulated ranger says about itself (VV, PP).
struct HokuyoModel {
  std::string vendor = "Hokuyo Automatic Co.,Ltd.";  ///< VV VEND
  std::string product;                               ///< VV PROD
  std::string firmware;                              ///< VV FIRM
  std::string protocol = "SCIP 2.0";                 ///< VV PROT
  std::string serial = "H0000001";                   ///< VV SERI
  std::string model_name;                            ///< PP MODL
  scip::ScanGeometry geometry;

  /// URG-04LX (the specification's figures): DMIN 20, DMAX 5600, ARES 1024, AMIN 44,
  /// AMAX 725, AFRT 384, 600 rpm: 682 steps of 0.3515625°, 100 ms a scan.
  static HokuyoModel urg04lx();
  /// UBG-05LN as the seed paper reports it: 513 points 0.36° apart (ARES 1000) up to 4500 mm.
  /// Chosen here (not published figures): AFRT 500 and AMIN/AMAX 244/756, i.e. 256 steps each
  /// side of straight ahead (±92.16°, as the simulator's laser); DMIN 20; 600 rpm.
  static HokuyoModel ubg05ln();
};

/// Ranges in mm for the steps AMIN…AMAX of scan number `scan_index` (0, 1, …). Values below
/// DMIN act as error codes, values above DMAX as "no echo"; a vector of another size is cut
/// or padded with 0.
using RangeSource = std::function<std::vector<std::uint32_t>(std::uint64_t scan_index)>;

/// A named test pattern for `model` (a fixed scan, the same every time):
///  "ramp": distances rising along the scan, with an error code (7) every 50 steps and a
///          value above DMAX every 61 steps;
///  "room": the walls of a 6 m × 4 m room seen from 1.5 m off its centre (above DMAX → no echo);
///  "constant": 1000 mm everywhere.
/// Throws std::invalid_argument for another name.
RangeSource hokuyoRangePattern(const std::string& name, const HokuyoModel& model);
/// The raw values (steps AMIN…AMAX) of `source` for one scan, sized to the model.
std::vector<std::uint32_t> modelRanges(const RangeSource& source, std::uint64_t scan_index,
                                       const HokuyoModel& model);
/// The values a request reads from a model's ranges: the minimum of each cluster.
std::vector<std::uint32_t> requestedValues(const std::vector<std::uint32_t>& model_ranges,
                                           const HokuyoModel& model,
                                           const scip::ScanRequest& request);

class ScipResponder {
 public:
  struct Options {
    bool start_in_scip11 = false;    ///< answer SCIP 1.1 until "SCIP2.0" arrives
    bool support_time_sync = true;   ///< TM0/1/2 (false: "undefined command", as old firmware)
    bool laser_malfunction = false;  ///< BM answers "01"
  };

  ScipResponder(HokuyoModel model, RangeSource ranges, Options options);
  ScipResponder(HokuyoModel model, RangeSource ranges)
      : ScipResponder(std::move(model), std::move(ranges), Options{}) {}

  /// Back to the power-on state: laser off, no stream, the start protocol.
  void powerOn();
  /// The reply to one request line (no LF/CR); empty for an empty line. `now_ms`: the
  /// device's 24-bit millisecond counter now.
  std::string respond(std::string_view line, std::uint32_t now_ms);
  /// For one mirror turn while streaming: that scan's reply, or nothing when the interval
  /// skips it. The stream ends after its count of scans.
  std::optional<std::string> streamTurn(std::uint32_t stamp_ms);

  bool streaming() const { return stream_.has_value(); }
  const std::optional<scip::ScanRequest>& stream() const { return stream_; }
  bool speaksScip2() const { return scip2_; }
  bool laserOn() const { return laser_on_; }
  const HokuyoModel& model() const { return model_; }

 private:
  std::string respondScip11(std::string_view line);
  std::string respondScan(std::string_view echo, std::string_view command, std::uint32_t now_ms);
  std::string respondTimeSync(std::string_view echo, std::string_view command,
                              std::uint32_t now_ms);
  std::string respondBeamOn(std::string_view echo);
  std::string scanReply(const std::string& echo, std::string_view status,
                        const scip::ScanRequest& request, std::uint32_t stamp_ms);
  std::vector<std::string> versionLines() const;
  std::vector<std::string> parameterLines() const;
  std::vector<std::string> stateLines(std::uint32_t now_ms) const;

  HokuyoModel model_;
  RangeSource ranges_;
  Options options_;
  bool scip2_ = true;
  bool laser_on_ = false;
  bool time_sync_mode_ = false;
  std::optional<scip::ScanRequest> stream_;
  int stream_turn_ = 0;
  int stream_left_ = 0;  ///< scans still to send; -1: until QT
  std::uint64_t scans_taken_ = 0;
};

}  // namespace mrslam::drivers
