#pragma once
// The part of libphidget22's C API the encoder adapter uses, resolved at run time (dlopen /
// dlsym). Types mirror phidget22.h: handles are pointers to opaque structs, return codes are
// a C enum (int), EPHIDGET_OK = 0; timeChange of the position-change handler is in ms.

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "mrslam/common/result.hpp"

namespace mrslam::drivers::phidget {

struct PhidgetTag;
struct EncoderTag;
using Handle = PhidgetTag*;         ///< PhidgetHandle
using EncoderHandle = EncoderTag*;  ///< PhidgetEncoderHandle
using ReturnCode = int;             ///< PhidgetReturnCode
constexpr ReturnCode kOk = 0;       ///< EPHIDGET_OK

/// PhidgetEncoder_OnPositionChangeCallback.
using PositionChangeHandler = void (*)(EncoderHandle channel, void* context, int position_change,
                                       double time_change_ms, int index_triggered);

struct Library {
  std::string name;  ///< as it was asked for
  void* handle = nullptr;
  ReturnCode (*encoder_create)(EncoderHandle*) = nullptr;
  ReturnCode (*encoder_delete)(EncoderHandle*) = nullptr;
  ReturnCode (*set_device_serial_number)(Handle, std::int32_t) = nullptr;
  ReturnCode (*set_hub_port)(Handle, int) = nullptr;
  ReturnCode (*set_channel)(Handle, int) = nullptr;
  ReturnCode (*open_wait_for_attachment)(Handle, std::uint32_t) = nullptr;
  ReturnCode (*close)(Handle) = nullptr;
  ReturnCode (*set_on_position_change_handler)(EncoderHandle, PositionChangeHandler,
                                               void*) = nullptr;
  ReturnCode (*get_position)(EncoderHandle, std::int64_t*) = nullptr;
  ReturnCode (*set_data_interval)(EncoderHandle, std::uint32_t) = nullptr;
  ReturnCode (*get_error_description)(ReturnCode, const char**) = nullptr;

  /// "Timed Out (code 3)" from Phidget_getErrorDescription.
  std::string describe(ReturnCode code) const;
};

/// The first of `names` that loads and exports every function; else why none did.
Result<std::shared_ptr<const Library>> loadLibrary(const std::vector<std::string>& names);

/// An encoder handle where the API wants the base PhidgetHandle (a cast in C).
inline Handle asPhidget(EncoderHandle channel) {
  return reinterpret_cast<Handle>(channel);
}

}  // namespace mrslam::drivers::phidget
