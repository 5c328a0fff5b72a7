// Fuzz target: the BreezySLAM log reader on arbitrary bytes.
#include "log_reader_fuzz_common.hpp"
#include "mrslam/drivers/breezyslam_reader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  mrslam::fuzz::readWholeLog<mrslam::drivers::BreezySlamReader,
                             mrslam::drivers::BreezySlamSettings>(data, size);
  return 0;
}
