#pragma once
// What the fullscreen passes share: one per-pixel body, two forms. A
// fullscreen pass's shader is a body in glsl/ (`struct PassOutputs {...};
// PassOutputs shadePixel(ivec2 pixel)`, reading its inputs with texelFetch
// and writing every output on every pixel, background included: nothing
// relies on discard or a pre-clear). The body runs under one of two entries:
//   fragment: fullscreen.vert's one triangle + glsl/fullscreen_entry.frag,
//             the outputs as colour attachments;
//   compute:  glsl/fullscreen_entry.comp, kPassGroupSize-square groups, the
//             outputs as images of their own format (RGBA16F or RGBA32F).
// A pass names which PassOutputs member goes to which texture (PassOutput);
// the program for (variant, form, outputs) is built on first use and kept.
// Accumulated frames (--ssgi-frames) blend in the entry, not in fixed-function
// blending, so both forms average alike.
#include <map>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "frame/frame_plan.hpp"
#include "gl/objects.hpp"
#include "gl/shader_library.hpp"

namespace headlight {

// The most outputs a fullscreen pass writes (the entries declare four).
inline constexpr std::size_t kMaxPassOutputs = 4;

// One output of a fullscreen pass: the body's PassOutputs member written to `texture`.
struct PassOutput {
  std::string_view member;
  const gl::Texture* texture = nullptr;
};

// What selects the entry around a body: its form, whether it accumulates,
// and its outputs (member and the texture's internal format) in order.
struct PassEntry {
  PassForm form = PassForm::Fragment;
  bool accumulates = false;
  std::vector<std::pair<std::string, GLenum>> outputs;
  auto operator<=>(const PassEntry&) const = default;
};
PassEntry passEntry(PassForm form, std::span<const PassOutput> outputs, bool accumulates);

// Builds `body` (a glsl/ file) under `entry` with the body's own `defines`.
// Throws GlError with the compiler's log.
gl::Program buildPassProgram(std::string_view body, const PassEntry& entry, std::span<const std::string> defines);

// Runs a fullscreen pass's program over `outputs` (all of one size) in
// `entry`'s form. Owns the framebuffer and the empty vertex array of the
// fragment form; targets are detached after the draw, so a dropped target is
// not kept alive by the framebuffer. `accumulateWeight` (programs built with
// accumulates): 0 overwrites, w blends in as (1 - w) previous + w new.
class FullscreenRunner {
 public:
  FullscreenRunner();
  // `what` names the pass in errors.
  void run(std::string_view what, const gl::Program& program, PassForm form, std::span<const PassOutput> outputs,
           std::optional<float> accumulateWeight = std::nullopt);

 private:
  gl::Framebuffer framebuffer_;
  gl::VertexArray emptyVertexArray_;  // a fullscreen triangle needs no vertices, but core GL needs a VAO bound
};

// A fullscreen pass's programs: one per (variant, entry), built on first
// use (so a frame compiles only what it runs) and kept. `Variant` is any
// ordered key (std::monostate for a pass without variants); `defines` maps
// it to the body's #defines.
template <class Variant>
class FullscreenPass {
 public:
  using Defines = std::vector<std::string> (*)(const Variant&);

 protected:
  FullscreenPass(std::string_view body, Defines defines) : body_(body), defines_(defines) {}
  void run(std::string_view what, const Variant& variant, PassForm form, std::span<const PassOutput> outputs,
           std::optional<float> accumulateWeight = std::nullopt) {
    runner_.run(what, program(variant, passEntry(form, outputs, accumulateWeight.has_value())), form, outputs,
                accumulateWeight);
  }
  const gl::Program& program(const Variant& variant, const PassEntry& entry) {
    auto key = std::make_pair(variant, entry);
    auto found = programs_.find(key);
    if (found != programs_.end()) return found->second;
    const std::vector<std::string> defines = defines_(variant);
    gl::Program built = buildPassProgram(body_, entry, defines);
    return programs_.emplace(std::move(key), std::move(built)).first->second;
  }

 private:
  std::string_view body_;  // the name of an embedded file: static storage
  Defines defines_;
  std::map<std::pair<Variant, PassEntry>, gl::Program> programs_;
  FullscreenRunner runner_;
};

}  // namespace headlight
