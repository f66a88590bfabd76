#pragma once
// The antialias pass (AntialiasStep, lib/frame/frame_plan.hpp): one
// jittered sample's lit into the running mean in lit.accumulation.
//   reads  lit (this sample's)
//   writes lit.accumulation  sample 0 overwrites it, sample s blends in with weight 1 / (s + 1)
//          lit.foreground    the same for RGB x A and A (AntialiasStep::foreground)
// Body: glsl/antialias.glsl, in either form.
#include <variant>
#include <vector>

#include "passes/frame_pass.hpp"
#include "passes/fullscreen.hpp"

namespace headlight {

class AntialiasPass final : public FramePass, FullscreenPass<std::monostate> {
 public:
  AntialiasPass();
  // The sample is FrameInputs::antialiasSample.
  void execute(const FrameInputs& inputs, const PassAttachments& attachments, PassForm form) override;
};

}  // namespace headlight
