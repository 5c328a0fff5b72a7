// The 3DM-GX1 stream parser: frames out of a byte stream, resynchronising after bad bytes.

#include "mrslam/drivers/gx1_codec.hpp"

namespace mrslam::drivers::gx1 {

namespace {

constexpr std::size_t kCompactAfter = 1024;  // bytes consumed before the buffer is shifted

}  // namespace

StreamParser::StreamParser()
    : StreamParser({kEulerCommand, kEulerVectorsCommand, kQuaternionVectorsCommand,
                    kEepromReadCommand, kContinuousCommand}) {}

StreamParser::StreamParser(const std::vector<std::uint8_t>& headers) {
  accept(headers);
}

void StreamParser::accept(const std::vector<std::uint8_t>& headers) {
  accepted_.fill(false);
  for (const std::uint8_t header : headers) {
    accepted_[header] = frameSize(header) > 0;
  }
}

void StreamParser::push(const std::uint8_t* data, std::size_t size) {
  compact();
  buffer_.insert(buffer_.end(), data, data + size);
}

std::optional<Frame> StreamParser::next() {
  while (pending() > 0) {
    const std::uint8_t header = buffer_[head_];
    if (!accepted_[header]) {
      ++counters_.garbage_bytes;
      ++head_;
      continue;
    }
    const std::size_t size = frameSize(header);
    if (pending() < size) {
      return std::nullopt;  // the rest of a candidate frame is still on its way
    }
    if (std::optional<Frame> frame = decodeFrame(buffer_.data() + head_, size)) {
      head_ += size;
      ++counters_.frames;
      return frame;
    }
    // Slide by one byte only: a real header may sit inside the rejected candidate.
    ++counters_.bad_checksums;
    ++head_;
  }
  return std::nullopt;
}

void StreamParser::discardPartial() {
  if (pending() > 0) {
    ++counters_.truncated_frames;
  }
  clear();
}

void StreamParser::clear() {
  buffer_.clear();
  head_ = 0;
}

void StreamParser::compact() {
  if (head_ == buffer_.size()) {
    clear();
  } else if (head_ >= kCompactAfter) {
    buffer_.erase(buffer_.begin(), buffer_.begin() + static_cast<std::ptrdiff_t>(head_));
    head_ = 0;
  }
}

}  // namespace mrslam::drivers::gx1
