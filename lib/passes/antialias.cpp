#include "passes/antialias.hpp"

namespace headlight {

AntialiasPass::AntialiasPass()
    : FullscreenPass("antialias.glsl", [](const std::monostate&) { return std::vector<std::string>{}; }) {}

void AntialiasPass::execute(const FrameInputs& inputs, const PassAttachments& attachments, PassForm form) {
  std::vector<PassOutput> outputs{{"lit", &attachments.write(Attachment::LitAccumulation)}};
  if (inputs.plan.antialias->foreground)
    outputs.push_back({"foreground", &attachments.write(Attachment::LitForeground)});
  const int sample = inputs.antialiasSample;
  FullscreenPass::run("antialias", std::monostate{}, form, outputs, sample == 0 ? 0.0f : 1.0f / float(sample + 1));
}

}  // namespace headlight
