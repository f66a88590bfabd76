// Bounded reads of regular files (io/bounded_read.hpp).
#include "io/bounded_read.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>

#include "headlight/error.hpp"

namespace headlight::detail {
namespace {

namespace fs = std::filesystem;

std::string kindOf(mode_t mode) {
  if (S_ISREG(mode)) return "";
  if (S_ISDIR(mode)) return "a folder";
  if (S_ISFIFO(mode)) return "a FIFO (named pipe)";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a regular file";
}

// Closes the descriptor on every path out.
struct FileDescriptor {
  int fd = -1;
  ~FileDescriptor() {
    if (fd >= 0) ::close(fd);
  }
};

}  // namespace

std::string byteSizeText(std::uint64_t bytes) {
  char text[48];
  if (bytes < 1024)
    std::snprintf(text, sizeof text, "%llu bytes", static_cast<unsigned long long>(bytes));
  else if (bytes < (std::uint64_t(1) << 20))
    std::snprintf(text, sizeof text, "%.1f KiB", double(bytes) / 1024.0);
  else if (bytes < (std::uint64_t(1) << 30))
    std::snprintf(text, sizeof text, "%.1f MiB", double(bytes) / double(1 << 20));
  else
    std::snprintf(text, sizeof text, "%.1f GiB", double(bytes) / double(1 << 30));
  return text;
}

std::string excerpt(std::string_view text, std::size_t maxChars) {
  std::string out;
  for (std::size_t i = 0; i < text.size(); ++i) {
    if (out.size() >= maxChars) {
      out += "... (" + std::to_string(text.size()) + " bytes)";
      break;
    }
    const unsigned char c = static_cast<unsigned char>(text[i]);
    if (c >= 0x20 && c < 0x7f) {
      out += char(c);
    } else {
      char escaped[8];
      std::snprintf(escaped, sizeof escaped, "\\x%02x", c);
      out += escaped;
    }
  }
  return out;
}

std::string nonRegularKind(const fs::path& path) {
  struct stat info {};
  if (::stat(path.c_str(), &info) != 0) return "";  // missing: the open reports it
  return kindOf(info.st_mode);
}

std::string readRegularFile(const fs::path& path, std::uint64_t maxBytes, std::string_view what) {
  const std::string where = path.string() + ": cannot read " + std::string(what) + ": ";
  // O_NONBLOCK: opening a FIFO without a writer returns at once instead of
  // waiting; fstat then refuses it. Checked on the descriptor, so a file
  // swapped after a stat cannot slip through.
  FileDescriptor file{::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY)};
  if (file.fd < 0) throw IoError(where + std::strerror(errno));
  struct stat info {};
  if (::fstat(file.fd, &info) != 0) throw IoError(where + "fstat: " + std::strerror(errno));
  if (const std::string kind = kindOf(info.st_mode); !kind.empty())
    throw IoError(where + "is " + kind + ", expected a regular file");
  if (std::uint64_t(info.st_size) > maxBytes)
    throw IoError(where + "is " + byteSizeText(std::uint64_t(info.st_size)) + ", more than the " +
                  byteSizeText(maxBytes) + " such a file may have");
  std::string bytes;
  bytes.resize(std::size_t(info.st_size));
  std::size_t filled = 0;
  // Read until EOF, but never past the limit (a file growing while read).
  for (;;) {
    if (filled == bytes.size()) {
      if (bytes.size() > maxBytes)
        throw IoError(where + "grew past the " + byteSizeText(maxBytes) + " such a file may have while being read");
      bytes.resize(std::min<std::size_t>(std::size_t(maxBytes) + 1, bytes.size() + 65536));
    }
    const ssize_t got = ::read(file.fd, bytes.data() + filled, bytes.size() - filled);
    if (got < 0) {
      if (errno == EINTR) continue;
      throw IoError(where + "read: " + std::strerror(errno));
    }
    if (got == 0) break;
    filled += std::size_t(got);
  }
  bytes.resize(filled);
  return bytes;
}

}  // namespace headlight::detail
