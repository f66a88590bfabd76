// What `render` writes reads back through OpenImageIO with the right
// channel names, pixel types, size, orientation and metadata; writes are
// atomic and failures leave nothing behind.
#include <doctest/doctest.h>

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imageio.h>

#include <chrono>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <thread>

#include "headlight/error.hpp"
#include "headlight/output.hpp"
#include "headlight/scene_loader.hpp"
#include "io/folder_lock.hpp"
#include "support/gl.hpp"
#include "support/temp_folder.hpp"

using namespace headlight;
namespace fs = std::filesystem;

namespace {

const Frame& cornellFrame() {
  static const Frame frame = [] {
    Renderer renderer(test::sharedContext());
    renderer.setScene(loadScene("builtin:cornell"));
    return renderer.render(test::smallSettings(72, 56));
  }();
  return frame;
}

}  // namespace

TEST_CASE("writeFrame: every target reads back with its channels, type, size and values") {
  const Frame& frame = cornellFrame();
  const fs::path folder = test::freshFolder("exr_roundtrip");
  const auto written = writeFrame(frame, folder);
  CHECK(written.size() == frame.targets().size() + 1);  // + preview.png
  for (const auto& [name, image] : frame.targets()) {
    CAPTURE(name);
    OIIO::ImageBuf file((folder / (name + ".exr")).string());
    REQUIRE(file.read(0, 0, true, OIIO::TypeDesc::FLOAT));
    const OIIO::ImageSpec& spec = file.spec();
    CHECK(spec.width == image->width);
    CHECK(spec.height == image->height);
    CHECK(spec.nchannels == image->channelCount());
    const bool isFloat = name == "position" || name == "depth";
    if (name == "ids") {
      // Integers, read as integers (as float OpenImageIO would scale them to 0..1): exact.
      CHECK(file.nativespec().format == OIIO::TypeDesc::UINT);
      auto input = OIIO::ImageInput::open((folder / "ids.exr").string());
      REQUIRE(input);
      std::vector<std::uint32_t> ids(image->pixels.size());
      REQUIRE(input->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::UINT, ids.data()));
      std::size_t differing = 0;
      for (std::size_t p = 0; p < std::size_t(image->width * image->height); ++p)
        for (int c = 0; c < image->channelCount(); ++c)
          differing +=
              ids[p * std::size_t(spec.nchannels) + std::size_t(spec.channelindex(image->channels[std::size_t(c)]))] !=
              std::uint32_t(image->pixels[p * std::size_t(image->channelCount()) + std::size_t(c)]);
      CHECK(differing == 0);
      continue;
    }
    CHECK(file.nativespec().format == (isFloat ? OIIO::TypeDesc::FLOAT : OIIO::TypeDesc::HALF));
    // OpenEXR stores channels sorted by name; look each up by name.
    for (int c = 0; c < image->channelCount(); ++c) {
      const int index = spec.channelindex(image->channels[std::size_t(c)]);
      REQUIRE(index >= 0);
      // Top row first: pixel (x, y) of the file is pixel (x, y) of the frame.
      for (int y : {0, image->height / 2, image->height - 1}) {
        const float expected = image->at(image->width / 2, y, c);
        const float actual = file.getchannel(image->width / 2, y, 0, index);
        CHECK(actual == doctest::Approx(expected).epsilon(isFloat ? 1e-7 : 1e-3).scale(1.0));
      }
    }
  }
  fs::remove_all(folder);
}

TEST_CASE("EXR orientation: the top row of position.exr is higher in the world than the bottom row") {
  const fs::path folder = test::freshFolder("exr_orientation");
  writeFrame(cornellFrame(), folder);
  OIIO::ImageBuf file((folder / "position.exr").string());
  const int y = file.spec().channelindex("position.Y");
  const int x = file.spec().width / 2;
  CHECK(file.getchannel(x, 2, 0, y) > file.getchannel(x, file.spec().height - 3, 0, y) + 0.5f);
  fs::remove_all(folder);
}

TEST_CASE("EXR metadata says what produced the image") {
  const Frame& frame = cornellFrame();
  const fs::path folder = test::freshFolder("exr_metadata");
  writeFrame(frame, folder);
  OIIO::ImageBuf file((folder / "lit.exr").string());
  const OIIO::ImageSpec& spec = file.spec();
  const OIIO::ParamValue* worldToCamera = spec.find_attribute("worldToCamera", OIIO::TypeDesc::TypeMatrix44);
  REQUIRE(worldToCamera != nullptr);
  const float* m = static_cast<const float*>(worldToCamera->data());
  // OpenEXR's row-vector matrix: translation in the last row.
  CHECK(m[12] == doctest::Approx(frame.view.view[3][0]));
  CHECK(m[14] == doctest::Approx(frame.view.view[3][2]));
  CHECK(spec.find_attribute("worldToNDC", OIIO::TypeDesc::TypeMatrix44) != nullptr);
  CHECK(spec.get_float_attribute("headlight:near") == doctest::Approx(frame.view.nearPlane));
  CHECK(spec.get_float_attribute("headlight:far") == doctest::Approx(frame.view.farPlane));
  CHECK(spec.get_string_attribute("headlight:renderer") == frame.glRenderer);
  CHECK(spec.get_string_attribute("headlight:backend") == frame.backend);
  CHECK(spec.get_string_attribute("headlight:scene") == "builtin:cornell");
  CHECK(spec.get_string_attribute("headlight:sceneHash").size() == 16);
  CHECK(spec.get_string_attribute("headlight:setting:width") == "72");
  CHECK(spec.get_string_attribute("headlight:setting:ssgi-samples") == "64");
  // "auto" is recorded as the number it resolved to.
  CHECK(std::stof(spec.get_string_attribute("headlight:setting:ssgi-radius")) ==
        doctest::Approx(*frame.settings.ssgi.radius));
  fs::remove_all(folder);
}

TEST_CASE("writes are atomic: no temporary file stays, and a failed write leaves nothing") {
  const Frame& frame = cornellFrame();
  const fs::path folder = test::freshFolder("exr_atomic");
  writeFrame(frame, folder);
  for (const auto& entry : fs::directory_iterator(folder)) {
    CAPTURE(entry.path());
    CHECK(entry.path().filename().string().front() != '.');
  }
  // A folder that cannot be made (a file is in the way): IoError, no output.
  const fs::path blocked = folder / "lit.exr" / "sub";
  CHECK_THROWS_AS(writeFrame(frame, blocked), IoError);
  CHECK_FALSE(fs::exists(blocked));
  fs::remove_all(folder);
}

TEST_CASE(
    "writeFrame holds the folder's lock: a folder locked elsewhere is refused, one this process holds is shared") {
  const Frame& frame = cornellFrame();
  const fs::path folder = test::freshFolder("exr_lock");
  OutputOptions options;
  options.targets = {"lit"};
  {
    // Another holder of the folder's flock, as another process's render is.
    const int fd = ::open(folder.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    REQUIRE(fd >= 0);
    REQUIRE(::flock(fd, LOCK_EX) == 0);
    try {
      writeFrame(frame, folder, options);
      FAIL("a locked folder was written");
    } catch (const IoError& error) {
      CHECK(std::string(error.what()).find(folder.string()) != std::string::npos);
      CHECK(std::string(error.what()).find("wait for it") != std::string::npos);
      CHECK(error.settings() == std::vector<std::string>{"wait"});
    }
    // Waited for, the folder is given up after waitForFolderSeconds, naming the holder's lock.
    OutputOptions waiting = options;
    waiting.waitForFolder = true;
    waiting.waitForFolderSeconds = 0.2;
    try {
      writeFrame(frame, folder, waiting);
      FAIL("a locked folder was written");
    } catch (const IoError& error) {
      CHECK(std::string(error.what()).find("still holds the folder's lock after 0.2 s of waiting") !=
            std::string::npos);
      CHECK(error.settings() == std::vector<std::string>{"wait-timeout"});
    }
    CHECK(!fs::exists(folder / "lit.exr"));
    ::close(fd);
  }
  // The CLI's way: its own lock from before the render, then writeFrame on
  // its writer thread, which it shares the lock with: the nested lock must
  // not wait for the first.
  {
    const detail::OutputFolderLock held(folder, false);
    std::thread([&] {
      const detail::OutputFolderLock::ThreadShare share(held);
      CHECK(writeFrame(frame, folder, options).size() == 1);
    }).join();
  }
  CHECK(fs::exists(folder / "lit.exr"));
  // Another thread the holder did not share it with (two Python threads
  // calling Frame.write into one folder mixed their files, issue 32) is kept
  // out as another process is: refused at once, or after --wait-timeout.
  {
    const detail::OutputFolderLock held(folder, false);
    std::thread([&] {
      try {
        writeFrame(frame, folder, options);
        FAIL("another thread wrote into a held folder");
      } catch (const IoError& error) {
        CHECK(std::string(error.what()).find("another thread of this process") != std::string::npos);
      }
      OutputOptions waiting = options;
      waiting.waitForFolder = true;
      waiting.waitForFolderSeconds = 0.2;
      CHECK_THROWS_WITH_AS(writeFrame(frame, folder, waiting), doctest::Contains("after 0.2 s of waiting"), IoError);
    }).join();
    // The holder's own thread takes it again freely.
    CHECK(writeFrame(frame, folder, options).size() == 1);
  }
  // Released: the other thread writes, and a waiting one gets the folder as
  // soon as the holder lets go.
  std::thread([&] { CHECK(writeFrame(frame, folder, options).size() == 1); }).join();
  {
    auto held = std::make_unique<detail::OutputFolderLock>(folder, false);
    OutputOptions waiting = options;
    waiting.waitForFolder = true;
    waiting.waitForFolderSeconds = 30;
    std::thread writer([&] { CHECK(writeFrame(frame, folder, waiting).size() == 1); });
    std::this_thread::sleep_for(std::chrono::milliseconds(300));
    held.reset();
    writer.join();
  }
  // Released: a second flock succeeds at once.
  const int fd = ::open(folder.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  CHECK(::flock(fd, LOCK_EX | LOCK_NB) == 0);
  ::close(fd);
  fs::remove_all(folder);
}

TEST_CASE("the lock is the folder: a folder renamed during a render gets its set, the new one under its name none") {
  // `mv out out.old; mkdir out` while a render holds `out` (issue 32): the
  // render's files went by name into the new, empty `out`, and the folder it
  // had locked stayed empty. Now they go where the lock is; messages keep
  // the name the caller gave.
  const Frame& frame = cornellFrame();
  const fs::path parent = test::freshFolder("lock_follows_folder");
  const fs::path out = parent / "out", moved = parent / "out.old";
  OutputOptions options;
  options.targets = {"lit"};
  {
    const detail::OutputFolderLock held(out, false);
    fs::rename(out, moved);
    fs::create_directory(out);
    const std::vector<WrittenFile> written = writeFrame(frame, out, options);
    REQUIRE(written.size() == 1);
    CHECK(written[0].path == out / "lit.exr");
    CHECK(written[0].summary.rfind(out.string() + "/lit.exr: ", 0) == 0);
    CHECK(written[0].summary.find("/proc/self/fd") == std::string::npos);
    // While the first still holds `out.old`, another lock on the new `out` is free.
    std::thread([&] {
      const detail::OutputFolderLock other(out, false);
      CHECK(fs::exists(out));
    }).join();
  }
  CHECK(fs::exists(moved / "lit.exr"));
  CHECK(fs::exists(moved / "frame.json"));
  CHECK(fs::is_empty(out));
  fs::remove_all(parent);
}
