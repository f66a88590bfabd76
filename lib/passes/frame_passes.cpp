// The GL side of each fullscreen pass row (fullscreenPassRows(),
// lib/frame/frame_plan.cpp): a pass with GL code of its own is made here by
// its row's name; a row with a body and no entry here runs as a
// GenericFramePass.
#include <stdexcept>

#include "headlight/error.hpp"
#include "passes/antialias.hpp"
#include "passes/composite.hpp"
#include "passes/direct_light.hpp"
#include "passes/frame_pass.hpp"
#include "passes/ssgi.hpp"
#include "passes/ssgi_blur.hpp"

namespace headlight {
namespace {

template <class Pass>
std::unique_ptr<FramePass> make() {
  return std::make_unique<Pass>();
}

struct OwnPass {
  std::string_view row;
  std::unique_ptr<FramePass> (*make)();
};
constexpr OwnPass kOwnPasses[] = {
    {"direct", make<DirectLightPass>},  {"ssgi", make<SsgiPass>},           {"ssgi-blur", make<SsgiBlurPass>},
    {"composite", make<CompositePass>}, {"antialias", make<AntialiasPass>},
};

}  // namespace

std::unique_ptr<FramePass> makeFramePass(std::size_t index) {
  const FullscreenPassRow& row = fullscreenPassRows()[index];
  for (const OwnPass& own : kOwnPasses)
    if (own.row == row.name) return own.make();
  if (!row.body.empty()) return std::make_unique<GenericFramePass>(row);
  throw GlError(std::string(row.name) + ": a fullscreen pass with neither GL code of its own nor a body");
}

}  // namespace headlight
