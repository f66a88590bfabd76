#pragma once
// What every part of the glTF loader shares: the file being read with its
// parsed model, and the words its messages use. Every failure is a
// SceneError (or a LimitError) that starts with the file name and names the
// glTF element, so a malformed file is a message, never a crash.
//
// Debian's libtinygltf.so carries the implementation (and its JSON parser),
// so the loader only includes the declarations: no TINYGLTF_IMPLEMENTATION.
#include <tiny_gltf.h>

#include <cstddef>
#include <string>

#include "headlight/error.hpp"
#include "io/message_text.hpp"

namespace headlight::gltf {

std::string countOf(std::size_t count, const char* noun);  // "1 node", "3 nodes", "2 vertices"
std::string componentTypeName(int componentType);          // "UNSIGNED_SHORT"
std::string typeName(int type);                            // "VEC3"
std::string modeName(int mode);                            // "TRIANGLE_STRIP"

// The file's name (as given) and its parsed model.
struct Source {
  std::string file;
  const tinygltf::Model& model;

  // `settings`: the settings the message names (Error::settings(); the CLI words them as flags).
  [[noreturn]] void fail(const std::string& message, std::vector<std::string> settings = {}) const {
    throw SceneError(file + ": " + message, std::move(settings));
  }
  [[noreturn]] void failLimit(const std::string& message, const std::string& setting) const {
    throw LimitError(file + ": " + message, {setting});
  }

  // `user` refers to element `index` of `container` (the file's `noun`s).
  template <typename Container>
  void checkIndex(int index, const Container& container, const std::string& user, const char* noun) const {
    if (index < 0 || static_cast<std::size_t>(index) >= container.size()) {
      fail(user + " refers to " + noun + " " + std::to_string(index) + ", but the file has " +
           countOf(container.size(), noun));
    }
  }
};

}  // namespace headlight::gltf
