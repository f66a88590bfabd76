#include "passes/composite.hpp"

#include "shared_layout.h"

namespace headlight {

CompositePass::CompositePass()
    : FullscreenPass("composite.glsl", [](const CompositeVariant& variant) {
        std::vector<std::string> defines;
        if (variant.ssgi) defines.emplace_back("HAS_SSGI");
        if (variant.sky) defines.emplace_back("HAS_SKY");
        if (variant.environment) defines.emplace_back("HAS_ENVIRONMENT");
        for (std::string& define : lobeDefines(variant.lobes)) defines.push_back(std::move(define));
        return defines;
      }) {}

void CompositePass::execute(const FrameInputs& inputs, const PassAttachments& attachments, PassForm form) {
  const CompositeVariant& variant = *inputs.plan.composite;
  bindAmbientTables(inputs.environment, variant.sky, variant.environment);
  const PassOutput outputs[] = {{"radiance", &attachments.write(Attachment::Lit)}};
  FullscreenPass::run("composite", variant, form, outputs);
}

}  // namespace headlight
