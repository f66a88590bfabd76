// Embedding Headlight: render a scene into memory and read its pixels. Build
// against an installed Headlight with nothing but pkg-config:
//
//   c++ -std=c++20 embed.cpp $(pkg-config --cflags --libs headlight) -o embed
//   ./embed                       # the built-in Cornell box, backend auto
//   ./embed osmesa                # the same on OSMesa
//   ./embed auto model.gltf       # a glTF file (textures, .glb, Draco: as the CLI loads them)
//
// Exit status 0 when the frame looks right (the Cornell box's centre lit;
// for a file, some pixel of its geometry lit), 1 otherwise.
#include <headlight/context.hpp>
#include <headlight/error.hpp>
#include <headlight/renderer.hpp>
#include <headlight/scene_loader.hpp>
#include <headlight/settings.hpp>
#include <headlight/version.hpp>
#include <iostream>
#include <string>

int main(int argc, char** argv) try {
  headlight::ContextOptions options;
  if (argc > 1) options.backend = headlight::parseBackend(argv[1]);
  const std::string scene = argc > 2 ? argv[2] : "builtin:cornell";
  headlight::Context context(options);  // current on this thread from here on
  headlight::Renderer renderer(context);
  renderer.setScene(headlight::loadScene(scene));

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
            << scene << ": lit(" << x << ", " << y << ") = " << r << " " << g << " " << b << " " << a << "\n";
  bool ok = lit.width == 96 && lit.height == 64;
  if (scene == "builtin:cornell") {
    ok = ok && a == 1.0f && r > 0.0f && g > 0.0f && b > 0.0f;
  } else {
    int litGeometry = 0;  // pixels of the file's geometry (A = 1) with light on them
    for (int py = 0; py < lit.height; ++py)
      for (int px = 0; px < lit.width; ++px)
        litGeometry += lit.at(px, py, 3) == 1.0f && lit.at(px, py, 0) + lit.at(px, py, 1) + lit.at(px, py, 2) > 0.0f;
    std::cout << scene << ": " << litGeometry << " lit geometry pixels\n";
    ok = ok && litGeometry > 0;
  }
  if (!ok) std::cerr << "embed: unexpected pixels\n";
  return ok ? 0 : 1;
} catch (const headlight::Error& error) {
  std::cerr << "embed: " << error.what() << "\n";
  return 1;
}
