// headlight-thumbnailer INPUT OUTPUT SIZE: a file manager's thumbnail of a
// glTF file (.gltf, .glb), as the freedesktop thumbnailer entry
// tools/headlight.thumbnailer (installed into share/thumbnailers/) runs it:
// the scene rendered SIZE x SIZE with the fast preset from its own camera
// (or one fitted to its bounds), tonemapped to an 8-bit sRGB PNG at OUTPUT
// (writePreview: preview.png's look, the sky behind the model). Exit 0 ok, 1 the file could not be thumbnailed
// (the message names it), 2 usage.
#include <charconv>
#include <cstdio>
#include <iostream>
#include <string>

#include "headlight/context.hpp"
#include "headlight/error.hpp"
#include "headlight/output.hpp"
#include "headlight/renderer.hpp"
#include "headlight/scene_loader.hpp"
#include "headlight/settings.hpp"
#include "tooling/large_pages.hpp"

int main(int argc, char** argv) {
  // File managers ask for 128, 256, 512 or 1024 (freedesktop's normal, large,
  // x-large and xx-large); more is refused rather than rendered for minutes.
  constexpr int kMaxSize = 4096;
  int size = 0;
  const std::string sizeText = argc == 4 ? argv[3] : "";
  const auto [end, error] = std::from_chars(sizeText.data(), sizeText.data() + sizeText.size(), size);
  if (argc != 4 || error != std::errc() || end != sizeText.data() + sizeText.size() || size < 1 || size > kMaxSize) {
    std::cerr << "usage: headlight-thumbnailer INPUT OUTPUT SIZE (a .gltf or .glb file, the PNG to write, 1.."
              << kMaxSize << " pixels a side)\n";
    return 2;
  }
  headlight::restartWithLargePages(argv);  // returns unless it restarts
  const std::string input = argv[1], output = argv[2];
  try {
    headlight::Context context;  // backend auto: EGL, then OSMesa
    headlight::Renderer renderer(context);
    renderer.setScene(headlight::loadScene(input));
    headlight::RenderSettings settings;
    headlight::applyPreset(settings, "fast");
    settings.width = settings.height = size;
    const std::string targets[] = {"lit"};  // the preview is made from lit alone
    headlight::writePreview(renderer.render(settings, nullptr, targets), output);
    return 0;
  } catch (const std::exception& failure) {
    std::cerr << "headlight-thumbnailer: " << input << ": " << failure.what() << "\n";
    return 1;
  }
}
