// Loading libphidget22 at run time and resolving the functions the encoder adapter uses.

#include "phidget_library.hpp"

#include <dlfcn.h>

#include <cstring>

namespace mrslam::drivers::phidget {

namespace {

// dlsym gives an object pointer; copy its bits into the function pointer (no cast warnings).
template <class Function>
bool resolve(void* library, const char* symbol, Function& function, std::string& missing) {
  void* address = ::dlsym(library, symbol);
  if (address == nullptr) {
    missing += missing.empty() ? symbol : std::string(", ") + symbol;
    return false;
  }
  static_assert(sizeof(function) == sizeof(address), "function and object pointers differ");
  std::memcpy(&function, &address, sizeof(address));
  return true;
}

// Every function of the API; the names of those missing are listed in `missing`.
void resolveAll(Library& l, std::string& missing) {
  void* h = l.handle;
  resolve(h, "PhidgetEncoder_create", l.encoder_create, missing);
  resolve(h, "PhidgetEncoder_delete", l.encoder_delete, missing);
  resolve(h, "Phidget_setDeviceSerialNumber", l.set_device_serial_number, missing);
  resolve(h, "Phidget_setHubPort", l.set_hub_port, missing);
  resolve(h, "Phidget_setChannel", l.set_channel, missing);
  resolve(h, "Phidget_openWaitForAttachment", l.open_wait_for_attachment, missing);
  resolve(h, "Phidget_close", l.close, missing);
  resolve(h, "PhidgetEncoder_setOnPositionChangeHandler", l.set_on_position_change_handler,
          missing);
  resolve(h, "PhidgetEncoder_getPosition", l.get_position, missing);
  resolve(h, "PhidgetEncoder_setDataInterval", l.set_data_interval, missing);
  resolve(h, "Phidget_getErrorDescription", l.get_error_description, missing);
}

}  // namespace

std::string Library::describe(ReturnCode code) const {
  const char* text = nullptr;
  if (get_error_description == nullptr || get_error_description(code, &text) != kOk ||
      text == nullptr) {
    return "error code " + std::to_string(code);
  }
  return std::string(text) + " (code " + std::to_string(code) + ")";
}

Result<std::shared_ptr<const Library>> loadLibrary(const std::vector<std::string>& names) {
  using Loaded = Result<std::shared_ptr<const Library>>;
  std::string tried;
  for (const std::string& name : names) {
    void* handle = ::dlopen(name.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (handle == nullptr) {
      const char* error = ::dlerror();
      tried += (tried.empty() ? "" : "; ") + std::string(error != nullptr ? error : name);
      continue;
    }
    auto library = std::make_shared<Library>();
    library->name = name;
    library->handle = handle;
    std::string missing;
    resolveAll(*library, missing);
    if (missing.empty()) {
      return Loaded::success(std::move(library));
    }
    ::dlclose(handle);
    tried += (tried.empty() ? "" : "; ") + name + " lacks " + missing + " (not libphidget22?)";
  }
  return Loaded::failure("cannot load libphidget22 (install the vendor's library): " +
                         (tried.empty() ? std::string("no library name given") : tried));
}

}  // namespace mrslam::drivers::phidget
