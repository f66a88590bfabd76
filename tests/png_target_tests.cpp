// render --png and preview.png's background: each target's look on pixels
// whose display values are known, written through writeFrame.
#include <doctest/doctest.h>

#include <OpenImageIO/imagebuf.h>

#include <algorithm>
#include <array>
#include <filesystem>

#include "headlight/error.hpp"
#include "headlight/output.hpp"
#include "support/images.hpp"
#include "support/temp_folder.hpp"

using namespace headlight;
namespace fs = std::filesystem;

namespace {

// Pixel (x, y)'s channel c (rows top first, channels interleaved).
float& at(ImageF& image, int x, int y, int c) {
  return image
      .pixels[(std::size_t(y) * std::size_t(image.width) + std::size_t(x)) * image.channels.size() + std::size_t(c)];
}

// A 4x2 frame: the left column shows geometry, the rest background (lit's
// and position's A = 0, depth at the far plane), except where a case sets more.
Frame smallFrame() {
  Frame frame;
  frame.settings.width = 4;
  frame.settings.height = 2;
  frame.view.farPlane = 10.0f;
  frame.lit = test::makeImage(4, 2, {"R", "G", "B", "A"}, 0.0f);
  frame.normal = test::makeImage(4, 2, {"normal.X", "normal.Y", "normal.Z"}, 0.0f);
  frame.depth = test::makeImage(4, 2, {"depth.Z"}, 10.0f);
  frame.albedo = test::makeImage(4, 2, {"albedo.R", "albedo.G", "albedo.B"}, 0.5f);
  frame.ssgi = test::makeImage(4, 2,
                               {"ao.Y", "indirect.R", "indirect.G", "indirect.B", "sky.Y", "indirectFar.R",
                                "indirectFar.G", "indirectFar.B", "specular.Y"},
                               0.5f);
  for (int y = 0; y < 2; ++y) {
    at(frame.lit, 0, y, 0) = at(frame.lit, 0, y, 1) = at(frame.lit, 0, y, 2) = 0.18f;
    at(frame.lit, 0, y, 3) = 1.0f;
  }
  frame.sceneSource = "builtin:synthetic";
  return frame;
}

// The 8-bit values of pixel (x, y) of a PNG.
std::array<int, 4> pixel(const fs::path& png, int x, int y) {
  // The file's bytes: PNG's alpha is unassociated, and OpenImageIO would otherwise premultiply on read.
  OIIO::ImageSpec config;
  config.attribute("oiio:UnassociatedAlpha", 1);
  OIIO::ImageBuf image(png.string(), 0, 0, nullptr, &config);
  REQUIRE(image.read(0, 0, true, OIIO::TypeDesc::UINT8));
  std::array<int, 4> values{0, 0, 0, 255};
  for (int c = 0; c < std::min(4, image.nchannels()); ++c)
    values[std::size_t(c)] = int(image.getchannel(x, y, 0, c) * 255.0f + 0.5f);
  return values;
}

int channels(const fs::path& png) {
  OIIO::ImageBuf image(png.string());
  REQUIRE(image.init_spec(png.string(), 0, 0));
  return image.nchannels();
}

}  // namespace

TEST_CASE("--png writes each target through its look: normals as colours, depth through viridis, AO as grey") {
  Frame frame = smallFrame();
  at(frame.normal, 0, 0, 2) = 1.0f;   // +Z
  at(frame.normal, 1, 0, 0) = -1.0f;  // -X
  at(frame.depth, 0, 0, 0) = 2.0f;    // nearest geometry
  at(frame.depth, 1, 0, 0) = 6.0f;    // farthest geometry; the rest is background
  const fs::path folder = test::freshFolder("png_targets");
  OutputOptions options;
  options.pngTargets = {"normal", "depth", "ssgi", "albedo", "emissive"};  // emissive: not in this frame
  const std::vector<WrittenFile> written = writeFrame(frame, folder, options);
  CHECK(std::count_if(written.begin(), written.end(), [](const WrittenFile& f) {
          return f.path.extension() == ".png";
        }) == 5);  // four targets and preview.png
  CHECK_FALSE(fs::exists(folder / "emissive.png"));

  // Unit vectors as (v + 1) / 2; a zero vector (no geometry) black.
  CHECK(pixel(folder / "normal.png", 0, 0) == std::array<int, 4>{128, 128, 255, 255});
  CHECK(pixel(folder / "normal.png", 1, 0) == std::array<int, 4>{0, 128, 128, 255});
  CHECK(pixel(folder / "normal.png", 2, 0) == std::array<int, 4>{0, 0, 0, 255});
  // Viridis: the nearest depth at its yellow end, the farthest at its purple
  // end (OpenImageIO's table: about (253, 231, 37) and (68, 1, 84)), the far
  // plane (background) black.
  const auto near = pixel(folder / "depth.png", 0, 0), far = pixel(folder / "depth.png", 1, 0);
  CHECK(near[0] > 230);
  CHECK(near[1] > 210);
  CHECK(near[2] < 60);
  CHECK(far[0] < 90);
  CHECK(far[1] < 20);
  CHECK(far[2] > 60);
  CHECK(pixel(folder / "depth.png", 3, 1) == std::array<int, 4>{0, 0, 0, 255});
  // AO 0.5 as grey 128; linear albedo 0.5 sRGB-encoded (188).
  CHECK(pixel(folder / "ssgi.png", 2, 1) == std::array<int, 4>{128, 128, 128, 255});
  CHECK(pixel(folder / "albedo.png", 2, 1) == std::array<int, 4>{188, 188, 188, 255});
  CHECK(channels(folder / "normal.png") == 3);

  // A later set without PNGs removes the earlier set's: they were ours.
  writeFrame(frame, folder);
  CHECK_FALSE(fs::exists(folder / "normal.png"));
  CHECK(fs::exists(folder / "normal.exr"));
  fs::remove_all(folder);
}

TEST_CASE("preview.png's background: the sky as lit has it, transparent with coverage as alpha, or a colour") {
  Frame frame = smallFrame();
  for (int x = 1; x < 4; ++x) at(frame.lit, x, 1, 2) = 0.5f;  // a blue sky behind, uncovered
  const fs::path folder = test::freshFolder("preview_background");
  writeFrame(frame, folder / "sky");
  const auto covered = pixel(folder / "sky" / "preview.png", 0, 1);
  CHECK(channels(folder / "sky" / "preview.png") == 3);
  CHECK(pixel(folder / "sky" / "preview.png", 2, 1)[2] > 100);  // the sky shows

  frame.settings.previewBackground = "transparent";
  writeFrame(frame, folder / "transparent");
  CHECK(channels(folder / "transparent" / "preview.png") == 4);
  CHECK(pixel(folder / "transparent" / "preview.png", 0, 1) == covered);  // alpha 255, colour as with the sky
  CHECK(pixel(folder / "transparent" / "preview.png", 2, 1) == std::array<int, 4>{0, 0, 0, 0});

  frame.settings.previewBackground = "#ff8000";
  writeFrame(frame, folder / "hex");
  CHECK(pixel(folder / "hex" / "preview.png", 2, 1) == std::array<int, 4>{255, 128, 0, 255});
  CHECK(pixel(folder / "hex" / "preview.png", 0, 1) == covered);
  frame.settings.previewBackground = "0,0.5,1";
  writeFrame(frame, folder / "triple");
  CHECK(pixel(folder / "triple" / "preview.png", 3, 1) == std::array<int, 4>{0, 128, 255, 255});

  // An antialiased edge pixel: half a red surface (radiance 0.8, 0, 0), half the blue sky. lit mixes
  // both; over a colour or transparent the preview shows the foreground (Frame::litForeground) alone.
  Frame edge = frame;
  const float mixed[] = {0.4f, 0.0f, 0.25f, 0.5f};
  for (int c = 0; c < 4; ++c) at(edge.lit, 2, 1, c) = mixed[c];
  const float surface[] = {0.8f, 0.0f, 0.0f, 1.0f};  // the same surface covering pixel (1, 1) whole
  for (int c = 0; c < 4; ++c) at(edge.lit, 1, 1, c) = surface[c];
  edge.litForeground = edge.lit;
  for (std::size_t p = 0; p < edge.litForeground.pixels.size(); p += 4)
    for (std::size_t c = 0; c < 3; ++c) edge.litForeground.pixels[p + c] *= edge.litForeground.pixels[p + 3];
  const float foreground[] = {0.4f, 0.0f, 0.0f, 0.5f};  // 0.8 x 0.5: the surface's share, no sky
  for (int c = 0; c < 4; ++c) at(edge.litForeground, 2, 1, c) = foreground[c];
  edge.settings.previewBackground = "transparent";
  writeFrame(edge, folder / "edge");
  const auto shown = pixel(folder / "edge" / "preview.png", 2, 1);
  CHECK(shown[3] == 128);  // the coverage
  CHECK(shown[2] == 0);    // no sky under the surface's colour
  const auto whole = pixel(folder / "edge" / "preview.png", 1, 1);
  CHECK(whole[0] > 100);
  CHECK(shown[0] == whole[0]);  // the surface's red, unpremultiplied: as where it covers the pixel
  CHECK(pixel(folder / "edge" / "preview.png", 0, 1) == covered);  // whole pixels as before
  edge.litForeground = ImageF{};                                   // without it: lit's RGB, the sky mixed in
  writeFrame(edge, folder / "edge-lit");
  CHECK(pixel(folder / "edge-lit" / "preview.png", 2, 1)[2] > 50);

  // A background that is none of these is refused naming the setting, before anything is written.
  for (const char* bad : {"blue", "#ff80", "#gg0000", "1,0", "0,0,2", "0,0,nan", ""}) {
    CAPTURE(bad);
    frame.settings.previewBackground = bad;
    CHECK_THROWS_WITH_AS(frame.settings.validate(), doctest::Contains("preview-background"), SettingsError);
    CHECK_THROWS_AS(writeFrame(frame, folder / "refused"), SettingsError);
    CHECK_FALSE(fs::exists(folder / "refused"));
  }
  fs::remove_all(folder);
}

TEST_CASE("OutputOptions::pngTargets refuses a name that is no frame target") {
  OutputOptions options;
  options.pngTargets = {"preview"};
  const fs::path folder = test::freshFolder("png_unknown");
  CHECK_THROWS_WITH_AS(writeFrame(smallFrame(), folder / "out", options), doctest::Contains("PNG target 'preview'"),
                       SettingsError);
  CHECK_FALSE(fs::exists(folder / "out"));
  fs::remove_all(folder);
}
