// The output folder's advisory lock (output/folder_lock.hpp).
#include "output/folder_lock.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <map>
#include <mutex>

#include "headlight/error.hpp"

namespace headlight::detail {

namespace fs = std::filesystem;

namespace {

// This process's folder locks: the flocked descriptor and how many
// OutputFolderLock objects share it.
struct HeldFolder {
  int fd = -1;
  int holders = 0;
};
std::mutex heldMutex;
std::map<std::string, HeldFolder> held;

std::string folderKey(int fd, const fs::path& folder) {
  struct stat status{};
  if (::fstat(fd, &status) != 0) throw IoError(folder.string() + ": cannot stat the output folder: " + std::strerror(errno));
  return std::to_string(status.st_dev) + ":" + std::to_string(status.st_ino);
}

// Takes the flock on `fd`; closes it and throws if it cannot.
void flockOrThrow(int fd, const fs::path& folder, bool wait) {
  while (::flock(fd, LOCK_EX | (wait ? 0 : LOCK_NB)) != 0) {
    if (errno == EINTR) continue;
    const int savedErrno = errno;
    ::close(fd);
    if (savedErrno == EWOULDBLOCK)
      throw IoError(folder.string() +
                        ": another Headlight process is writing into this folder (it holds the folder's lock); "
                        "wait for it, or choose another output folder",
                    {"wait"});
    throw IoError(folder.string() + ": cannot lock the output folder: " + std::strerror(savedErrno));
  }
}

}  // namespace

OutputFolderLock::OutputFolderLock(const fs::path& folder, bool wait) : folder_(folder) {
  std::error_code error;
  created_ = fs::create_directories(folder, error);
  if (error) throw IoError(folder.string() + ": cannot create the output folder: " + error.message());
  const int fd = ::open(folder.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) throw IoError(folder.string() + ": cannot open the output folder to lock it: " + std::strerror(errno));
  std::string key;
  try {
    key = folderKey(fd, folder);
  } catch (...) {
    ::close(fd);
    throw;
  }
  {
    const std::lock_guard guard(heldMutex);
    if (HeldFolder& entry = held[key]; entry.holders > 0) {
      ++entry.holders;  // this process holds it already: share it
      ::close(fd);
      key_ = key;
      return;
    }
  }
  // Not under the mutex: waiting for another process must not stop this
  // one's other folders.
  try {
    flockOrThrow(fd, folder, wait);
  } catch (...) {
    const std::lock_guard guard(heldMutex);
    if (held[key].holders == 0) held.erase(key);
    throw;
  }
  const std::lock_guard guard(heldMutex);
  HeldFolder& entry = held[key];
  if (entry.holders > 0) {
    ::close(fd);  // another thread of this process took it meanwhile: share theirs
  } else {
    entry.fd = fd;
  }
  ++entry.holders;
  key_ = key;
}

OutputFolderLock::~OutputFolderLock() {
  const std::lock_guard guard(heldMutex);
  auto found = held.find(key_);
  if (found == held.end() || --found->second.holders > 0) return;
  if (created_) {
    std::error_code ignored;
    if (fs::is_empty(folder_, ignored) && !ignored) fs::remove(folder_, ignored);
  }
  ::close(found->second.fd);  // closing drops the flock
  held.erase(found);
}

}  // namespace headlight::detail
