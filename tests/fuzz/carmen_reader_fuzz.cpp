// Fuzz target: the CARMEN log reader on arbitrary bytes.
#include "log_reader_fuzz_common.hpp"
#include "mrslam/drivers/carmen_reader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  mrslam::fuzz::readWholeLog<mrslam::drivers::CarmenReader, mrslam::drivers::CarmenSettings>(data,
                                                                                             size);
  return 0;
}
