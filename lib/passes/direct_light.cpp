#include "passes/direct_light.hpp"

#include "shared_layout.h"

namespace headlight {

DirectLightPass::DirectLightPass()
    : FullscreenPass("direct_light.glsl", [](const DirectLightVariant& variant) {
        std::vector<std::string> defines;
        if (variant.emissive) defines.emplace_back("HAS_EMISSIVE");
        appendShadowDefines(variant.shadows, defines);
        if (variant.diffuseTarget) defines.emplace_back("WRITE_DIFFUSE_RADIANCE");
        for (std::string& define : lobeDefines(variant.lobes)) defines.push_back(std::move(define));
        return defines;
      }) {}

void DirectLightPass::execute(const FrameInputs& inputs, const PassAttachments& attachments, PassForm form) {
  const DirectLightVariant& variant = *inputs.plan.direct;
  bindShadowMaps(inputs.shadows, variant.shadows);
  const PassOutput outputs[] = {
      {"towardEye", &attachments.write(Attachment::DirectTowardEye)},
      {"diffuse", variant.diffuseTarget ? &attachments.write(Attachment::DirectDiffuse) : nullptr}};
  FullscreenPass::run("direct light", variant, form, std::span(outputs, variant.diffuseTarget ? 2 : 1));
}

}  // namespace headlight
