// The image half of io/atomic_file.hpp: OpenImageIO writers into the
// temporary name. Part of the image module (lib/image_io/image_module.hpp).
#include "image_io/atomic_image.hpp"

#include <OpenImageIO/imageio.h>

#include <cerrno>

#include "headlight/error.hpp"
#include "io/atomic_file.hpp"

namespace headlight::detail {

namespace fs = std::filesystem;

void writePixelsAtomically(const fs::path& path, const void* pixels, OIIO::TypeDesc pixelType,
                           const OIIO::ImageSpec& spec, const char* format) {
  writeAtomically(path, [&](const fs::path& temporary) {
    auto output = OIIO::ImageOutput::create(format);
    if (!output) throw IoError(path.string() + ": OpenImageIO has no " + format + " writer: " + OIIO::geterror());
    errno = 0;
    const bool ok = output->open(temporary.string(), spec) && output->write_image(pixelType, pixels);
    const int openWriteErrno = errno;
    const bool closed = output->close();
    const int savedErrno = ok ? errno : openWriteErrno;
    if (!ok || !closed)
      throw IoError(path.string() + ": writing failed: " + writeFailureReason(path, output->geterror(), savedErrno));
  });
}

void writeImageAtomically(const fs::path& path, const OIIO::ImageBuf& buffer, const OIIO::ImageSpec& spec,
                          const char* format) {
  writeAtomically(path, [&](const fs::path& temporary) {
    auto output = OIIO::ImageOutput::create(format);
    if (!output) throw IoError(path.string() + ": OpenImageIO has no " + format + " writer: " + OIIO::geterror());
    errno = 0;
    const bool ok = output->open(temporary.string(), spec) && buffer.write(output.get());
    const int openWriteErrno = errno;
    const bool closed = output->close();
    const int savedErrno = ok ? errno : openWriteErrno;
    if (!ok || !closed)
      throw IoError(path.string() + ": writing failed: " + writeFailureReason(path, output->geterror(), savedErrno));
  });
}

}  // namespace headlight::detail
