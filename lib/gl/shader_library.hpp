#pragma once
// Shader sources from glsl/, embedded at build time (glsl/embed.py), so the
// binary runs from any directory. Programs are built from a list of stage
// files plus #defines; `#include "x"` lines are expanded from the same table.
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "gl/objects.hpp"

namespace headlight::detail {

struct EmbeddedShader {
  const char* name;  // file name in glsl/, e.g. "ssgi.frag"
  const char* text;
};
std::span<const EmbeddedShader> embeddedShaders();  // generated

// The text of glsl/<name>; throws GlError if there is no such file.
std::string_view shaderText(std::string_view name);

// "#version 450 core", then one "#define D" per entry of `defines` (each may
// carry a value: "SAMPLE_COUNT 16"), then the file with its includes
// expanded (each file at most once). #line directives keep compiler messages
// pointing at the right line of the right file (numbered by include order).
std::string buildShaderSource(std::string_view fileName, std::span<const std::string> defines);
// The same for one stage made of several files in order (a fullscreen pass's
// body, then its entry), included files shared: each at most once.
std::string buildShaderSource(std::span<const std::string_view> files, std::span<const std::string> defines);

// Compiles and links a program from stage files (the stage is taken from the
// extension: .vert, .frag, .comp). Throws GlError with the compiler's log.
gl::Program buildProgram(std::span<const std::string_view> files, std::span<const std::string> defines = {});
// The same with each stage made of several files (the last one's extension
// names the stage).
struct StageFiles {
  std::span<const std::string_view> files;
};
gl::Program buildProgram(std::span<const StageFiles> stages, std::span<const std::string> defines);

}  // namespace headlight::detail
