// Fuzz target: the mrslam log reader on arbitrary bytes (after a valid header line).
#include <cstring>

#include "log_reader_fuzz_common.hpp"
#include "mrslam/drivers/mrslam_log.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::string text = std::string(mrslam::drivers::kMrslamLogMagic) + "\n";
  text.append(reinterpret_cast<const char*>(data), size);
  mrslam::fuzz::readWholeLog<mrslam::drivers::MrslamLogReader, mrslam::drivers::MrslamLogSettings>(
      reinterpret_cast<const std::uint8_t*>(text.data()), text.size());
  return 0;
}
