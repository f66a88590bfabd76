// The output folder's advisory lock (output/folder_lock.hpp).
#include "output/folder_lock.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "headlight/error.hpp"

namespace headlight::detail {

namespace fs = std::filesystem;

OutputFolderLock::OutputFolderLock(const fs::path& folder, bool wait) : folder_(folder) {
  std::error_code error;
  created_ = fs::create_directories(folder, error);
  if (error) throw IoError(folder.string() + ": cannot create the output folder: " + error.message());
  fd_ = ::open(folder.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd_ < 0) throw IoError(folder.string() + ": cannot open the output folder to lock it: " + std::strerror(errno));
  while (::flock(fd_, LOCK_EX | (wait ? 0 : LOCK_NB)) != 0) {
    if (errno == EINTR) continue;
    const int savedErrno = errno;
    ::close(fd_);
    fd_ = -1;
    if (savedErrno == EWOULDBLOCK)
      throw IoError(folder.string() +
                    ": another Headlight process is writing into this folder (it holds the folder's lock); pass "
                    "--wait to wait for it, or choose another --out");
    throw IoError(folder.string() + ": cannot lock the output folder: " + std::strerror(savedErrno));
  }
}

OutputFolderLock::~OutputFolderLock() {
  if (created_) {
    std::error_code ignored;
    if (fs::is_empty(folder_, ignored) && !ignored) fs::remove(folder_, ignored);
  }
  if (fd_ >= 0) ::close(fd_);  // closing drops the flock
}

}  // namespace headlight::detail
