#pragma once
// What the diff tests share: small EXRs written with OpenImageIO (a gradient,
// unit normals and their rotation by a known angle) and the diff command run
// in-process. Included by diff_tests.cpp and diff_cli_tests.cpp only.
#include <doctest/doctest.h>

#include <OpenImageIO/imageio.h>

#include <cmath>
#include <filesystem>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "diff_command.hpp"

namespace headlight::test {

struct TestImage {
  int width = 8, height = 8;
  std::vector<std::string> channels{"R", "G", "B"};
  std::vector<float> pixels;
  float far = 0;  // written as headlight:far when > 0

  float& at(int x, int y, int c) {
    return pixels[(std::size_t(y) * std::size_t(width) + std::size_t(x)) * channels.size() + std::size_t(c)];
  }
};

// A smooth gradient in 0.1..0.9, different per channel.
inline TestImage gradient(int width, int height, std::vector<std::string> channels) {
  TestImage image;
  image.width = width;
  image.height = height;
  image.channels = std::move(channels);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      for (std::size_t c = 0; c < image.channels.size(); ++c)
        image.pixels.push_back(0.1f + 0.8f * float((x + 2 * y + 3 * int(c)) % 17) / 16.0f);
  return image;
}

inline void write(const std::filesystem::path& path, const TestImage& image) {
  OIIO::ImageSpec spec(image.width, image.height, int(image.channels.size()), OIIO::TypeDesc::FLOAT);
  spec.channelnames = image.channels;
  if (image.far > 0) spec.attribute("headlight:far", image.far);
  auto output = OIIO::ImageOutput::create(path.string());
  REQUIRE(output);
  REQUIRE(output->open(path.string(), spec));
  REQUIRE(output->write_image(OIIO::TypeDesc::FLOAT, image.pixels.data()));
  REQUIRE(output->close());
}

struct Cli {
  int exitCode = -1;
  std::string out, err;
};

inline Cli runCli(std::vector<std::string> args) {
  std::ostringstream out, err;
  Cli cli;
  cli.exitCode = cli::runDiffCommand(args, out, err);
  cli.out = out.str();
  cli.err = err.str();
  return cli;
}

inline bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

// Unit normals in many directions (none axis-aligned), background (0) in the first row.
inline TestImage normals() {
  TestImage image;
  image.width = 16;
  image.height = 16;
  image.channels = {"normal.X", "normal.Y", "normal.Z"};
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      if (y == 0) {
        image.pixels.insert(image.pixels.end(), {0.0f, 0.0f, 0.0f});
        continue;
      }
      const double theta = 0.1 + 2.9 * x / 15.0, phi = 0.3 + 6.0 * y / 15.0;
      image.pixels.insert(image.pixels.end(), {float(std::sin(theta) * std::cos(phi)), float(std::cos(theta)),
                                               float(std::sin(theta) * std::sin(phi))});
    }
  return image;
}

// Rotates every vector by `degrees` about an axis perpendicular to it, so
// each normal moves by exactly that angle.
inline TestImage rotated(TestImage image, double degrees) {
  const double angle = degrees * std::numbers::pi / 180.0;
  for (std::size_t p = 0; p < image.pixels.size(); p += 3) {
    const double n[3] = {image.pixels[p], image.pixels[p + 1], image.pixels[p + 2]};
    if (n[0] == 0 && n[1] == 0 && n[2] == 0) continue;
    // t = normalize(n x (0.3, 0.5, 0.8)) is perpendicular to n; rotate towards it.
    double t[3] = {n[1] * 0.8 - n[2] * 0.5, n[2] * 0.3 - n[0] * 0.8, n[0] * 0.5 - n[1] * 0.3};
    const double length = std::sqrt(t[0] * t[0] + t[1] * t[1] + t[2] * t[2]);
    for (int i = 0; i < 3; ++i)
      image.pixels[p + std::size_t(i)] = float(std::cos(angle) * n[i] + std::sin(angle) * t[i] / length);
  }
  return image;
}
}  // namespace headlight::test
