#pragma once
// Move-only owners of Embree 3 handles (device, scene, geometry): each
// destructor releases its one handle, a moved-from object owns nothing.
// Embree reports errors through a device callback; EmbreeDevice::check turns
// the first one since the last check into an Error naming the operation.
#include <embree3/rtcore.h>

#include <memory>
#include <string>

namespace headlight::reference {

// "RTC_ERROR_INVALID_ARGUMENT" for RTC_ERROR_INVALID_ARGUMENT, and so on.
const char* embreeErrorName(RTCError code);

class EmbreeDevice {
 public:
  // `config` is rtcNewDevice's configuration string ("" for Embree's
  // defaults). Throws Error when Embree cannot make a device.
  explicit EmbreeDevice(const std::string& config);
  ~EmbreeDevice();
  EmbreeDevice(EmbreeDevice&& other) noexcept;
  EmbreeDevice& operator=(EmbreeDevice&& other) noexcept;
  EmbreeDevice(const EmbreeDevice&) = delete;
  EmbreeDevice& operator=(const EmbreeDevice&) = delete;

  RTCDevice get() const { return device_; }

  // Throws Error naming `operation` if Embree reported an error since the
  // last check.
  void check(const std::string& operation);

 private:
  // The first error the callback saw (possibly on one of Embree's build
  // threads). On the heap so that the callback's pointer survives a move.
  struct ErrorLog;
  static void onError(void* user, RTCError code, const char* text);

  RTCDevice device_ = nullptr;
  std::unique_ptr<ErrorLog> log_;
};

class EmbreeScene {
 public:
  EmbreeScene() = default;
  explicit EmbreeScene(RTCDevice device) : scene_(rtcNewScene(device)) {}
  ~EmbreeScene();
  EmbreeScene(EmbreeScene&& other) noexcept;
  EmbreeScene& operator=(EmbreeScene&& other) noexcept;
  EmbreeScene(const EmbreeScene&) = delete;
  EmbreeScene& operator=(const EmbreeScene&) = delete;

  RTCScene get() const { return scene_; }

 private:
  RTCScene scene_ = nullptr;
};

// A geometry while it is being filled; a scene it is attached to keeps its
// own reference, so this one is released when the builder is done with it.
class EmbreeGeometry {
 public:
  EmbreeGeometry(RTCDevice device, RTCGeometryType type) : geometry_(rtcNewGeometry(device, type)) {}
  ~EmbreeGeometry();
  EmbreeGeometry(EmbreeGeometry&& other) noexcept;
  EmbreeGeometry& operator=(EmbreeGeometry&& other) noexcept;
  EmbreeGeometry(const EmbreeGeometry&) = delete;
  EmbreeGeometry& operator=(const EmbreeGeometry&) = delete;

  RTCGeometry get() const { return geometry_; }

 private:
  RTCGeometry geometry_ = nullptr;
};

}  // namespace headlight::reference
