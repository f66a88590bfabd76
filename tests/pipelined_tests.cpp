// Pipelined rendering (Renderer::submit / collect): frame N+1's passes are
// queued before frame N's pixels are read, and every frame must still be
// exactly the frame render() gives, whatever is queued behind it.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <glad/gl.h>

#include "color/srgb.hpp"
#include "gl/objects.hpp"
#include "gl/readback.hpp"
#include "headlight/camera.hpp"
#include "headlight/error.hpp"
#include "headlight/frame.hpp"
#include "headlight/renderer.hpp"
#include "headlight/scene_loader.hpp"
#include "headlight/targets.hpp"
#include "support/gl.hpp"

namespace headlight {
namespace {

// Every target of `a` equals `b`'s, pixel for pixel.
void checkSameTargets(const Frame& a, const Frame& b) {
  int compared = 0;
  for (const FrameTarget& target : frameTargets()) {
    if (target.image == nullptr) continue;
    CAPTURE(target.name);
    const ImageF& x = a.*target.image;
    const ImageF& y = b.*target.image;
    CHECK(x.width == y.width);
    CHECK(x.height == y.height);
    CHECK(x.channels == y.channels);
    CHECK(x.pixels == y.pixels);
    compared += !x.empty();
  }
  CHECK(compared >= 7);  // position, normal, albedo, material, depth, ssgi, lit
}

std::vector<Camera> orbit(const Scene& scene, int count) {
  std::vector<Camera> cameras;
  for (int i = 0; i < count; ++i)
    cameras.push_back(fitCamera(scene.worldBounds(), 1.0f, 0.8f, 6.2831853f * float(i) / float(count)));
  return cameras;
}

}  // namespace

TEST_CASE("pipelined: frames submitted ahead come back in order, each the frame render() gives") {
  const Scene scene = makeBuiltinScene("cornell");
  const RenderSettings settings = test::smallSettings(64, 64);
  const std::vector<Camera> cameras = orbit(scene, 3);
  Renderer renderer(test::sharedContext());
  renderer.setScene(scene);
  std::vector<Frame> expected;
  for (const Camera& camera : cameras) expected.push_back(renderer.render(settings, &camera));

  // Two in flight: N+1 is queued before N is collected.
  renderer.submit(settings, &cameras[0]);
  renderer.submit(settings, &cameras[1]);
  CHECK(renderer.submitted() == 2);
  CHECK_THROWS_WITH_AS(renderer.submit(settings, &cameras[2]),
                       "Renderer::submit: 2 frames are submitted and not collected (at most 2): collect() first",
                       SettingsError);
  const Frame first = renderer.collect();
  renderer.submit(settings, &cameras[2]);
  const Frame second = renderer.collect();
  const Frame third = renderer.collect();
  CHECK(renderer.submitted() == 0);
  CHECK_THROWS_WITH_AS(renderer.collect(), "Renderer::collect: no frame submitted", SettingsError);
  checkSameTargets(first, expected[0]);
  checkSameTargets(second, expected[1]);
  checkSameTargets(third, expected[2]);
  // The passes are named as render()'s (the once-per-scene ones ran in
  // render() already), and the readback is timed last.
  std::vector<std::string> names;
  for (const PassTime& time : second.timings) names.push_back(time.pass);
  CHECK(names ==
        std::vector<std::string>{"gbuffer", "direct", "ssgi-surface", "ssgi", "ssgi-blur", "composite", "readback"});
  for (const PassTime& time : expected[1].timings)
    if (time.pass != "shadows") CHECK(std::find(names.begin(), names.end(), time.pass) != names.end());
}

TEST_CASE("pipelined: a frame submitted before setScene is the old scene's, with the old scene's name") {
  const Scene cornell = makeBuiltinScene("cornell");
  const Scene spheres = makeBuiltinScene("spheres");
  const RenderSettings settings = test::smallSettings(48, 48);
  Renderer renderer(test::sharedContext());
  renderer.setScene(cornell);
  const Frame expected = renderer.render(settings);
  renderer.submit(settings);
  renderer.setScene(spheres);  // its upload and the next frame queue behind the pending copies
  renderer.submit(settings);
  const Frame old = renderer.collect();
  const Frame fresh = renderer.collect();
  CHECK(old.sceneSource == cornell.source);
  CHECK(fresh.sceneSource == spheres.source);
  checkSameTargets(old, expected);
  CHECK(fresh.lit.pixels != old.lit.pixels);
}

}  // namespace headlight

namespace headlight {

TEST_CASE("pipelined: a target read through a pixel buffer is the target read directly") {
  // llvmpipe reads directly (it copies at the call either way); a GPU through
  // pixel buffers: both paths must give the same image, whichever runs here.
  const Scene scene = makeBuiltinScene("spheres");
  Renderer renderer(test::sharedContext());
  renderer.setScene(scene);
  const RenderSettings settings = test::smallSettings(40, 30);
  const Frame frame = renderer.render(settings);
  // The frame's float images, uploaded into textures of the attachments' formats, read back both ways.
  struct Case {
    GLenum format;
    const ImageF* image;
  };
  for (const Case& c : {Case{GL_RGBA32F, &frame.position}, Case{GL_RGBA16F, &frame.normal},
                        Case{GL_SRGB8_ALPHA8, &frame.albedo}, Case{GL_RGBA8, &frame.material}}) {
    CAPTURE(c.format);
    const ImageF& image = *c.image;
    gl::Texture texture = gl::Texture::create2D(c.format, image.width, image.height);
    std::vector<float> rgba(std::size_t(image.width) * std::size_t(image.height) * 4, 1.0f);
    for (std::size_t p = 0; p < rgba.size() / 4; ++p)
      for (int ch = 0; ch < image.channelCount(); ++ch)
        rgba[p * 4 + std::size_t(ch)] = image.pixels[p * std::size_t(image.channelCount()) + std::size_t(ch)];
    glTextureSubImage2D(texture.id(), 0, 0, 0, image.width, image.height, GL_RGBA, GL_FLOAT, rgba.data());
    const gl::Texture* textures[] = {&texture};
    const ImageF direct = PendingImage::color(textures, image.channels, ReadPath::Direct).finish();
    const ImageF buffered = PendingImage::color(textures, image.channels, ReadPath::PixelBuffer).finish();
    CHECK(direct.width == buffered.width);
    CHECK(direct.channels == buffered.channels);
    CHECK(direct.pixels == buffered.pixels);
    CHECK(!direct.pixels.empty());
    // The upload took the image's top row as GL's bottom one: read back, each row comes back flipped.
    const std::size_t row = std::size_t(image.width) * std::size_t(image.channelCount());
    double largest = 0;
    for (int y = 0; y < image.height; ++y)
      for (std::size_t i = 0; i < row; ++i) {
        const float read = direct.pixels[std::size_t(y) * row + i];
        float expected = image.pixels[std::size_t(image.height - 1 - y) * row + i];
        // An upload stores the value as it is (no encoding); the read decodes the stored 8-bit code, alpha aside.
        if (c.format == GL_SRGB8_ALPHA8 && i % std::size_t(image.channelCount()) != 3)
          expected = srgbToLinear(std::round(std::clamp(expected, 0.0f, 1.0f) * 255.0f) / 255.0f);
        largest = std::max(largest, double(std::abs(read - expected)));
      }
    // Exact where the format holds a float; half-float rounding of normals for RGBA16F; half an 8-bit step for RGBA8.
    CHECK(largest <= (c.format == GL_RGBA32F   ? 0.0
                      : c.format == GL_RGBA16F ? 1e-3
                      : c.format == GL_RGBA8   ? 0.5 / 255.0 + 1e-6
                                               : 1e-6));
  }
  gl::Texture depth = gl::Texture::create2D(GL_DEPTH_COMPONENT32F, 8, 4);
  std::vector<float> depths(32);
  for (std::size_t i = 0; i < depths.size(); ++i) depths[i] = float(i) / 32.0f;
  glTextureSubImage2D(depth.id(), 0, 0, 0, 8, 4, GL_DEPTH_COMPONENT, GL_FLOAT, depths.data());
  const ImageF direct = PendingImage::viewDepth(depth, frame.view, "depth.Z", ReadPath::Direct).finish();
  const ImageF buffered = PendingImage::viewDepth(depth, frame.view, "depth.Z", ReadPath::PixelBuffer).finish();
  CHECK(direct.pixels == buffered.pixels);
  CHECK(direct.pixels.front() != direct.pixels.back());
}

TEST_CASE("pixel buffers are kept from one frame's readback for the next, one frame's worth") {
  test::sharedContext();  // current on this thread
  gl::Texture small = gl::Texture::create2D(GL_RGBA16F, 8, 4);
  gl::Texture large = gl::Texture::create2D(GL_RGBA16F, 16, 8);
  const std::vector<float> ones(16 * 8 * 4, 1.0f);
  glTextureSubImage2D(small.id(), 0, 0, 0, 8, 4, GL_RGBA, GL_FLOAT, ones.data());
  glTextureSubImage2D(large.id(), 0, 0, 0, 16, 8, GL_RGBA, GL_FLOAT, ones.data());
  const std::vector<std::string> channels{"R", "G", "B", "A"};
  ReadbackBuffers buffers;
  const gl::Texture* smallOnly[] = {&small};
  const gl::Texture* largeOnly[] = {&large};
  // Half-float textures travel as halves (transferType).
  const std::size_t smallBytes = 8 * 4 * 4 * 2, largeBytes = 16 * 8 * 4 * 2;
  PendingImage first = PendingImage::color(smallOnly, channels, ReadPath::PixelBuffer, &buffers);
  CHECK(buffers.keptBytes() == 0);  // in flight
  CHECK(first.finish().pixels == std::vector<float>(8 * 4 * 4, 1.0f));
  buffers.trim();
  CHECK(buffers.keptBytes() == smallBytes);
  // The next frame of the same size takes the kept buffer and gives it back.
  PendingImage second = PendingImage::color(smallOnly, channels, ReadPath::PixelBuffer, &buffers);
  CHECK(buffers.keptBytes() == 0);
  CHECK(second.finish().pixels == std::vector<float>(8 * 4 * 4, 1.0f));
  buffers.trim();
  CHECK(buffers.keptBytes() == smallBytes);
  // A frame of another size makes its own; the trim after it drops the old size's.
  PendingImage third = PendingImage::color(largeOnly, channels, ReadPath::PixelBuffer, &buffers);
  CHECK(buffers.keptBytes() == smallBytes);
  CHECK(third.finish().pixels == std::vector<float>(16 * 8 * 4, 1.0f));
  buffers.trim();
  CHECK(buffers.keptBytes() == largeBytes);
  // The direct path takes none.
  PendingImage direct = PendingImage::color(largeOnly, channels, ReadPath::Direct, &buffers);
  CHECK(buffers.keptBytes() == largeBytes);
  CHECK(direct.finish().pixels.size() == 16 * 8 * 4);
}

}  // namespace headlight
