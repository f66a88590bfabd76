#pragma once
// Shader variants, built on first use and kept: what each pass with
// #define-selected variants would otherwise write again.
#include <functional>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "gl/objects.hpp"
#include "gl/shader_library.hpp"

namespace headlight {

// One linked program per variant of a vertex + fragment shader pair, built
// on first use and kept for the cache's life. `Variant` is any ordered key
// (bool, an enum, a struct with a defaulted <=>); `defines` maps it to the
// #defines that select it.
template <class Variant>
class ProgramCache {
 public:
  using Defines = std::function<std::vector<std::string>(const Variant&)>;
  ProgramCache(std::string_view vertexFile, std::string_view fragmentFile, Defines defines)
      : files_{vertexFile, fragmentFile}, defines_(std::move(defines)) {}

  const gl::Program& get(const Variant& variant) {
    auto found = programs_.find(variant);
    if (found != programs_.end()) return found->second;
    const std::vector<std::string> defines = defines_(variant);
    return programs_.emplace(variant, detail::buildProgram(files_, defines)).first->second;
  }

 private:
  std::string_view files_[2];  // names of embedded files: static storage
  Defines defines_;
  std::map<Variant, gl::Program> programs_;
};

}  // namespace headlight
