#include "io/atomic_file.hpp"

#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <random>
#include <string>

#include "headlight/error.hpp"

namespace headlight::detail {
namespace {

namespace fs = std::filesystem;

// Hidden, ending in .tmp, unique per machine, process and call. The host
// name lets a writer on one node of a shared file system leave the
// temporaries of another node's live process alone.
fs::path temporaryPathFor(const fs::path& path) {
  thread_local std::mt19937 rng(std::random_device{}());
  static const std::string host = temporaryHostTag();
  std::string name = ".";
  name += path.filename().string();
  (name += '.') += host;
  (name += '.') += std::to_string(::getpid());
  (name += '-') += std::to_string(rng());
  name += ".tmp";
  return path.parent_path() / name;
}

}  // namespace

std::string temporaryHostTag() {
  char host[256] = {};
  if (::gethostname(host, sizeof host - 1) != 0 || host[0] == '\0') return "localhost";
  std::string tag(host);
  for (char& c : tag)
    if (c == '.' || c == '/') c = '_';
  return tag;
}

std::string writeFailureReason(const fs::path& path, std::string writerMessage, int savedErrno) {
  std::string reason = std::move(writerMessage);
  while (!reason.empty() && (reason.back() == '\n' || reason.back() == ' ')) reason.pop_back();
  if (savedErrno != 0) {
    const std::string system = std::strerror(savedErrno);
    if (reason.find(system) == std::string::npos) reason += (reason.empty() ? "" : ": ") + system;
  }
  // A full disk often reaches the writer as a short write with errno lost
  // (OpenEXR's exceptions); the free space says what happened. Only then:
  // a missing folder or a refused permission has its own errno, and
  // /proc's zero free bytes are no full disk.
  const bool unexplained = savedErrno == 0 || savedErrno == ENOSPC || savedErrno == EDQUOT || savedErrno == EIO;
  if (!unexplained) return reason.empty() ? "unknown reason (the writer gave none)" : reason;
  std::error_code error;
  const fs::space_info space = fs::space(path.parent_path().empty() ? fs::path(".") : path.parent_path(), error);
  if (!error && space.available < (1u << 20))
    reason += (reason.empty() ? "" : "; ") + std::string("only ") + std::to_string(space.available) +
              " bytes free on the file system (disk full?)";
  return reason.empty() ? "unknown reason (the writer gave none)" : reason;
}

void writeAtomically(const fs::path& path, const std::function<void(const fs::path&)>& write) {
  const fs::path temporary = temporaryPathFor(path);
  try {
    write(temporary);
    std::error_code error;
    fs::rename(temporary, path, error);
    if (error) throw IoError(path.string() + ": cannot move the finished file into place: " + error.message());
  } catch (...) {
    std::error_code ignored;
    fs::remove(temporary, ignored);
    throw;
  }
}

void writeTextAtomically(const fs::path& path, std::string_view text) {
  writeAtomically(path, [&](const fs::path& temporary) {
    errno = 0;
    FILE* file = std::fopen(temporary.c_str(), "wb");
    if (!file)
      throw IoError(path.string() + ": cannot create " + temporary.filename().string() + ": " +
                    writeFailureReason(path, "", errno));
    const bool wrote = std::fwrite(text.data(), 1, text.size(), file) == text.size() && std::fflush(file) == 0;
    const int savedErrno = errno;
    const bool closed = std::fclose(file) == 0;
    if (!wrote || !closed)
      throw IoError(path.string() + ": writing failed: " + writeFailureReason(path, "", wrote ? errno : savedErrno));
  });
}

}  // namespace headlight::detail
