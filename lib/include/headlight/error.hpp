#pragma once
// Every failure the library reports is one of these. Messages name the
// operation, the file or object, and expected against actual, so a caller can
// print what() and a user knows what to fix.
#include <stdexcept>
#include <string>
#include "headlight/export.hpp"

namespace headlight HEADLIGHT_PUBLIC {

class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
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

// A setting is out of its documented range.
class SettingsError : public Error {
 public:
  using Error::Error;
};

// A scene or a render asks for more than a ResourceLimits allows (memory,
// instances, triangles, texels). The message names the limit and its flag.
class LimitError : public Error {
 public:
  using Error::Error;
};

}  // namespace headlight
