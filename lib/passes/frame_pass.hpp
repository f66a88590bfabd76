#pragma once
// The GL side of the frame's fullscreen passes (their rows:
// FullscreenPassRow, lib/frame/frame_plan.cpp). A pass declares, per plan,
// the attachments it reads (on their texture units) and writes; the runner
// (runFramePass) binds the reads and hands the pass a PassAttachments that
// reaches only what it declared, so an undeclared read or write is an error
// at once, not a stale texture. What is not an attachment (shadow maps, the
// ambient tables, the virtual lights, the settings) comes in FrameInputs.
#include <array>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "frame/frame_plan.hpp"
#include "gl/objects.hpp"
#include "passes/environment.hpp"
#include "passes/fullscreen.hpp"
#include "passes/light_field.hpp"
#include "passes/shadow.hpp"
#include "passes/virtual_lights.hpp"

namespace headlight {

// The frame's attachments, by Attachment (empty where the plan allocated none).
using FrameTextures = std::array<gl::Texture, kAttachmentCount>;

// What a frame gives every fullscreen pass besides its attachments.
struct FrameInputs {
  const FramePlan& plan;
  const RenderSettings& settings;  // resolved
  const ShadowMaps& shadows;       // empty maps: no shadows
  const EnvironmentTables& environment;
  const VirtualLights& virtualLights;  // read where the plan's SSGI step gathers them
  const LightField& lightField;        // and the light field they fill (SsgiStep::lightFieldProbes)
  int antialiasSample = 0;             // the antialias pass's sample (AntialiasStep)
};

// The attachments one pass declared, and nothing else.
class PassAttachments {
 public:
  PassAttachments(const PassDeclaration& declaration, const FrameTextures& textures)
      : declaration_(declaration), textures_(textures) {}
  // A declared read (bound already on its unit) or write; throws GlError
  // naming the pass and the attachment for any other.
  const gl::Texture& read(Attachment id) const;
  const gl::Texture& write(Attachment id) const;
  bool declaresRead(Attachment id) const { return declaration_.readsAttachment(id); }
  const PassDeclaration& declaration() const { return declaration_; }
  std::string_view pass() const;

 private:
  const PassDeclaration& declaration_;
  const FrameTextures& textures_;
};

// A fullscreen pass's GL side: its programs (built on first use) and the
// draws of one frame.
class FramePass {
 public:
  virtual ~FramePass() = default;
  virtual void execute(const FrameInputs& inputs, const PassAttachments& attachments, PassForm form) = 0;
};

// Binds `declaration`'s reads on their units and executes `pass`. Throws
// GlError if a declared attachment was not allocated.
void runFramePass(FramePass& pass, const PassDeclaration& declaration, const FrameInputs& inputs,
                  const FrameTextures& textures, PassForm form);

// A pass with no GL code of its own (its row's body, defines and outputs):
// its program for the plan's defines, over its declared writes in order.
class GenericFramePass final : public FramePass, FullscreenPass<std::vector<std::string>> {
 public:
  explicit GenericFramePass(const FullscreenPassRow& row);
  void execute(const FrameInputs& inputs, const PassAttachments& attachments, PassForm form) override;

 private:
  const FullscreenPassRow& row_;
};

// The GL side of fullscreenPassRows()[row]: its own FramePass, or a
// GenericFramePass for a row with a body (lib/passes/frame_passes.cpp).
std::unique_ptr<FramePass> makeFramePass(std::size_t row);

}  // namespace headlight
