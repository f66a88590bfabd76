// The image module's entry point (lib/image_io/image_module.hpp): built only
// into libheadlight-image-io.so, next to the OpenImageIO code it points to.
#include "image_io/image_module.hpp"

namespace {

constexpr headlight::detail::ImageModuleTable kTable{
    headlight::detail::kImageModuleAbi,
    sizeof(headlight::detail::ImageModuleTable),
    &headlight::writeFrame,
    &headlight::writeExr,
    &headlight::writePreview,
    &headlight::readSettingAttributes,
    &headlight::diffImages,
    &headlight::diffDirectories,
    &headlight::writeDiffImages,
    &headlight::detail::decodeTexture,
    &headlight::detail::decodeEnvironment,
};

}  // namespace

extern "C" __attribute__((visibility("default"))) const headlight::detail::ImageModuleTable*
headlightImageModuleTable() {
  return &kTable;
}
