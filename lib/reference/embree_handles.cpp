#include "reference/embree_handles.hpp"

#include <mutex>
#include <utility>

#include "headlight/error.hpp"

namespace headlight::reference {

const char* embreeErrorName(RTCError code) {
  switch (code) {
    case RTC_ERROR_NONE:
      return "RTC_ERROR_NONE";
    case RTC_ERROR_UNKNOWN:
      return "RTC_ERROR_UNKNOWN";
    case RTC_ERROR_INVALID_ARGUMENT:
      return "RTC_ERROR_INVALID_ARGUMENT";
    case RTC_ERROR_INVALID_OPERATION:
      return "RTC_ERROR_INVALID_OPERATION";
    case RTC_ERROR_OUT_OF_MEMORY:
      return "RTC_ERROR_OUT_OF_MEMORY";
    case RTC_ERROR_UNSUPPORTED_CPU:
      return "RTC_ERROR_UNSUPPORTED_CPU";
    case RTC_ERROR_CANCELLED:
      return "RTC_ERROR_CANCELLED";
  }
  return "unknown RTCError";
}

// ---- EmbreeDevice ------------------------------------------------------------------

struct EmbreeDevice::ErrorLog {
  std::mutex mutex;
  std::string first;
};

EmbreeDevice::EmbreeDevice(const std::string& config) : log_(std::make_unique<ErrorLog>()) {
  device_ = rtcNewDevice(config.empty() ? nullptr : config.c_str());
  if (!device_)
    throw Error("traceReference: rtcNewDevice(\"" + config + "\") failed with " +
                embreeErrorName(rtcGetDeviceError(nullptr)) + " (does this CPU support SSE2?)");
  rtcSetDeviceErrorFunction(device_, &EmbreeDevice::onError, log_.get());
}

EmbreeDevice::~EmbreeDevice() {
  if (device_) rtcReleaseDevice(device_);
}

EmbreeDevice::EmbreeDevice(EmbreeDevice&& other) noexcept
    : device_(std::exchange(other.device_, nullptr)), log_(std::move(other.log_)) {}

EmbreeDevice& EmbreeDevice::operator=(EmbreeDevice&& other) noexcept {
  std::swap(device_, other.device_);
  std::swap(log_, other.log_);
  return *this;
}

void EmbreeDevice::check(const std::string& operation) {
  std::string message;
  {
    std::lock_guard<std::mutex> lock(log_->mutex);
    message = std::exchange(log_->first, std::string());
  }
  const RTCError code = rtcGetDeviceError(device_);
  if (message.empty() && code == RTC_ERROR_NONE) return;
  throw Error("traceReference: " + operation + ": Embree reported " +
              (message.empty() ? std::string(embreeErrorName(code)) : message));
}

void EmbreeDevice::onError(void* user, RTCError code, const char* text) {
  auto* log = static_cast<ErrorLog*>(user);
  std::lock_guard<std::mutex> lock(log->mutex);
  if (log->first.empty()) log->first = std::string(embreeErrorName(code)) + ": " + (text ? text : "");
}

// ---- EmbreeScene, EmbreeGeometry -----------------------------------------------------

EmbreeScene::~EmbreeScene() {
  if (scene_) rtcReleaseScene(scene_);
}

EmbreeScene::EmbreeScene(EmbreeScene&& other) noexcept : scene_(std::exchange(other.scene_, nullptr)) {}

EmbreeScene& EmbreeScene::operator=(EmbreeScene&& other) noexcept {
  std::swap(scene_, other.scene_);
  return *this;
}

EmbreeGeometry::~EmbreeGeometry() {
  if (geometry_) rtcReleaseGeometry(geometry_);
}

EmbreeGeometry::EmbreeGeometry(EmbreeGeometry&& other) noexcept
    : geometry_(std::exchange(other.geometry_, nullptr)) {}

EmbreeGeometry& EmbreeGeometry::operator=(EmbreeGeometry&& other) noexcept {
  std::swap(geometry_, other.geometry_);
  return *this;
}

}  // namespace headlight::reference
