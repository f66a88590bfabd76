#pragma once
// Every failure the library reports is one of these. Messages name the
// operation, the file or object, and expected against actual, so a caller can
// print what() and a user knows what to fix. A message names settings by
// their names ("camera 3: ...", "raise max-memory"), never by a command's
// flags; settings() lists the ones it names, so a front end can word them
// its own way (the headlight CLI prints "--camera", "--max-memory").
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "headlight/export.hpp"

namespace headlight HEADLIGHT_PUBLIC {

class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& message, std::vector<std::string> settings = {})
      : std::runtime_error(message),
        settings_(settings.empty() ? nullptr : std::make_shared<const std::vector<std::string>>(std::move(settings))) {}

  // The settings the message names, by their option-row names
  // (headlight/options.hpp), in the order they appear; often empty.
  const std::vector<std::string>& settings() const noexcept {
    static const std::vector<std::string> kNone;
    return settings_ ? *settings_ : kNone;
  }

 private:
  // Shared, so that copying an exception cannot throw.
  std::shared_ptr<const std::vector<std::string>> settings_;
};

// No OpenGL 4.5 core context could be made; the message lists every backend
// tried and why each failed.
class ContextError : public Error {
 public:
  using Error::Error;
};

// The scene file is unreadable, malformed or asks for something unsupported.
// The message starts with the file name and names the glTF element.
class SceneError : public Error {
 public:
  using Error::Error;
};

// Reading or writing an image or other file failed.
class IoError : public Error {
 public:
  using Error::Error;
};

// The GL reported an error through KHR_debug, or a shader failed to build.
class GlError : public Error {
 public:
  using Error::Error;
};

// A setting is out of its documented range, or settings contradict each
// other; the message starts with the setting's name, which settings() lists.
class SettingsError : public Error {
 public:
  using Error::Error;
};

// A scene or a render asks for more than a ResourceLimits allows (memory,
// instances, triangles, texels). The message names the limit's setting
// ("raise max-triangles"), which settings() lists.
class LimitError : public Error {
 public:
  using Error::Error;
};

}  // namespace headlight
