#include "passes/frame_pass.hpp"

#include "headlight/error.hpp"
#include "shared_layout.h"

namespace headlight {

std::string_view PassAttachments::pass() const { return fullscreenPassRows()[declaration_.row].name; }

const gl::Texture& PassAttachments::read(Attachment id) const {
  if (!declaration_.readsAttachment(id))
    throw GlError(std::string(pass()) + " reads " + std::string(attachmentRow(id).name) +
                  ", which its declaration does not name");
  return textures_[std::size_t(id)];
}

const gl::Texture& PassAttachments::write(Attachment id) const {
  if (!declaration_.writesAttachment(id))
    throw GlError(std::string(pass()) + " writes " + std::string(attachmentRow(id).name) +
                  ", which its declaration does not name");
  return textures_[std::size_t(id)];
}

void runFramePass(FramePass& pass, const PassDeclaration& declaration, const FrameInputs& inputs,
                  const FrameTextures& textures, PassForm form) {
  const std::string_view name = fullscreenPassRows()[declaration.row].name;
  auto require = [&](Attachment id) -> const gl::Texture& {
    const gl::Texture& texture = textures[std::size_t(id)];
    if (!texture) throw GlError(std::string(name) + ": " + std::string(attachmentRow(id).name) + " was not allocated");
    return texture;
  };
  for (const PassRead& read : declaration.reads) require(read.attachment).bind(read.unit);
  for (Attachment id : declaration.writes) require(id);
  pass.execute(inputs, PassAttachments(declaration, textures), form);
}

GenericFramePass::GenericFramePass(const FullscreenPassRow& row)
    : FullscreenPass(row.body, [](const std::vector<std::string>& defines) { return defines; }), row_(row) {}

void GenericFramePass::execute(const FrameInputs& inputs, const PassAttachments& attachments, PassForm form) {
  const std::vector<Attachment>& writes = attachments.declaration().writes;
  if (writes.size() != row_.outputs.size() || writes.size() > kMaxPassOutputs)
    throw GlError(std::string(row_.name) + " declares " + std::to_string(writes.size()) + " writes and names " +
                  std::to_string(row_.outputs.size()) + " outputs");
  std::vector<PassOutput> outputs;
  for (std::size_t i = 0; i < writes.size(); ++i) outputs.push_back({row_.outputs[i], &attachments.write(writes[i])});
  const std::vector<std::string> defines = row_.defines ? row_.defines(inputs.plan) : std::vector<std::string>{};
  FullscreenPass::run(row_.name, defines, form, outputs);
}

}  // namespace headlight
