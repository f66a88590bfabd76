// Embedding Headlight: render the built-in Cornell box into memory and read
// a pixel. Build against an installed Headlight with nothing but pkg-config:
//
//   c++ -std=c++20 embed.cpp $(pkg-config --cflags --libs headlight) -o embed
//   ./embed            # or: ./embed osmesa
//
// Exit status 0 when the frame looks like the Cornell box, 1 otherwise.
#include <headlight/context.hpp>
#include <headlight/error.hpp>
#include <headlight/renderer.hpp>
#include <headlight/scene_loader.hpp>
#include <headlight/settings.hpp>
#include <headlight/version.hpp>
#include <iostream>

int main(int argc, char** argv) try {
  headlight::ContextOptions options;
  if (argc > 1) options.backend = headlight::parseBackend(argv[1]);
  headlight::Context context(options);  // current on this thread from here on
  headlight::Renderer renderer(context);
  renderer.setScene(headlight::loadScene("builtin:cornell"));

  headlight::RenderSettings settings;
  settings.width = 96;
  settings.height = 64;
  settings.ssgi.sampleCount = 16;
  const headlight::Frame frame = renderer.render(settings);

  // Rows are top first; the centre of the Cornell box is lit geometry.
  const headlight::ImageF& lit = frame.lit;
  const int x = lit.width / 2, y = lit.height / 2;
  const float r = lit.at(x, y, 0), g = lit.at(x, y, 1), b = lit.at(x, y, 2), a = lit.at(x, y, 3);
  std::cout << "headlight " << headlight::kVersion << " on " << frame.backend << " (" << frame.glRenderer << ")\n"
            << "lit(" << x << ", " << y << ") = " << r << " " << g << " " << b << " " << a << "\n";
  const bool ok = lit.width == 96 && lit.height == 64 && a == 1.0f && r > 0.0f && g > 0.0f && b > 0.0f;
  if (!ok) std::cerr << "embed: unexpected pixel\n";
  return ok ? 0 : 1;
} catch (const headlight::Error& error) {
  std::cerr << "embed: " << error.what() << "\n";
  return 1;
}
