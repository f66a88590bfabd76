// The output folder's advisory lock (io/folder_lock.hpp).
#include "io/folder_lock.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <map>
#include <mutex>
#include <set>
#include <sstream>
#include <thread>

#include "headlight/error.hpp"

namespace headlight::detail {

namespace fs = std::filesystem;

namespace {

// This process's folder locks: the flocked descriptor, how many
// OutputFolderLock objects share it, and the threads that may share it (the
// one that took it, and those it was shared with).
struct HeldFolder {
  int fd = -1;
  int holders = 0;
  std::thread::id owner;
  std::multiset<std::thread::id> sharers;
  bool sharedWith(std::thread::id thread) const { return thread == owner || sharers.count(thread) > 0; }
};
std::mutex heldMutex;
std::map<std::string, HeldFolder> held;
// The spellings each held folder was locked by (absolute, normalised) -> its
// key: a later lock on the same spelling by a sharing thread is the held
// folder, even if the path now names another (the folder renamed, another
// made in its place), so the files go where the lock is.
std::map<std::string, std::string> heldSpellings;

std::string spelling(const fs::path& folder) {
  std::error_code error;
  const fs::path absolute = fs::absolute(folder, error);
  return (error ? folder : absolute).lexically_normal().string();
}

// Whether `folder` names the directory of `key` still (a renamed folder's
// old name may name another now, or nothing).
bool stillNames(const fs::path& folder, const std::string& key) {
  struct stat status {};
  return ::stat(folder.c_str(), &status) == 0 &&
         std::to_string(status.st_dev) + ":" + std::to_string(status.st_ino) == key;
}

std::string folderKey(int fd, const fs::path& folder) {
  struct stat status {};
  if (::fstat(fd, &status) != 0)
    throw IoError(folder.string() + ": cannot stat the output folder: " + std::strerror(errno));
  return std::to_string(status.st_dev) + ":" + std::to_string(status.st_ino);
}

// Takes the flock on `fd`, waiting up to `waitSeconds` where `wait`; closes
// it and throws if it cannot.
void flockOrThrow(int fd, const fs::path& folder, bool wait, double waitSeconds,
                  const std::function<void(const std::string&)>& waiting) {
  const auto start = std::chrono::steady_clock::now();
  bool told = false;
  while (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
    if (errno == EINTR) continue;
    const int savedErrno = errno;
    if (savedErrno != EWOULDBLOCK) {
      ::close(fd);
      throw IoError(folder.string() + ": cannot lock the output folder: " + std::strerror(savedErrno));
    }
    const double waited = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (!wait || waited >= waitSeconds) {
      const std::string holder = folderLockHolder(fd);
      ::close(fd);
      if (!wait)
        throw IoError(folder.string() + ": " + holder +
                          " holds this folder's lock (a render writing into it takes it); wait for it, or choose "
                          "another output folder",
                      {"wait"});
      char seconds[32];
      std::snprintf(seconds, sizeof seconds, "%g", waitSeconds);
      throw IoError(folder.string() + ": " + holder + " still holds the folder's lock after " + seconds +
                        " s of waiting; raise wait-timeout, or choose another output folder",
                    {"wait-timeout"});
    }
    if (!told && waiting) waiting(folderLockHolder(fd));
    told = true;
    // flock cannot time out: polled, at most 0.1 s late.
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
}

std::string readFirstLine(const fs::path& file) {
  std::ifstream in(file);
  std::string line;
  std::getline(in, line);
  return line;
}

}  // namespace

std::string folderLockHolder(int fd) {
  struct stat status {};
  if (::fstat(fd, &status) != 0) return "another process";
  // /proc/locks: "1: FLOCK  ADVISORY  WRITE 1234 08:01:5678 0 EOF", the device as the
  // kernel's major:minor in hex; a waiter's line has "->" after the number. A
  // file system stacked on another (overlayfs) may list the lower device: the
  // inode alone then decides, if one FLOCK lists it.
  char wanted[64];
  std::snprintf(wanted, sizeof wanted, "%02x:%02x:%lu", unsigned(major(status.st_dev)), unsigned(minor(status.st_dev)),
                static_cast<unsigned long>(status.st_ino));
  // Built by appending: GCC 12 warns falsely (-Wrestrict, bug 105329) on ":" + text.
  std::string inodeSuffix(1, ':');
  inodeSuffix.append(std::to_string(status.st_ino));
  std::ifstream locks("/proc/locks");
  std::string line, exact, byInode;
  int inodeMatches = 0;
  while (std::getline(locks, line)) {
    std::istringstream fields(line);
    std::string number, type, advisory, mode, pid, where;
    fields >> number >> type >> advisory >> mode >> pid >> where;
    if (type != "FLOCK") continue;
    if (where == wanted) exact = pid;
    if (where.size() > inodeSuffix.size() && where.ends_with(inodeSuffix)) {
      byInode = pid;
      ++inodeMatches;
    }
  }
  const std::string pid = !exact.empty() ? exact : inodeMatches == 1 ? byInode : "";
  if (pid.empty() || pid.find_first_not_of("0123456789") != std::string::npos) return "another process";
  if (pid == std::to_string(::getpid())) return "another thread of this process (" + pid + ")";
  const std::string name = readFirstLine(fs::path("/proc") / pid / "comm");
  return "process " + pid + (name.empty() ? "" : " (" + name + ")");
}

OutputFolderLock::OutputFolderLock(const fs::path& folder, bool wait, double waitSeconds,
                                   const std::function<void(const std::string& holder)>& waiting)
    : folder_(folder) {
  {
    const std::lock_guard guard(heldMutex);
    if (auto spelled = heldSpellings.find(spelling(folder)); spelled != heldSpellings.end())
      if (HeldFolder& entry = held[spelled->second];
          entry.holders > 0 && entry.sharedWith(std::this_thread::get_id())) {
        ++entry.holders;  // the folder this thread locked by this name, wherever it is now
        key_ = spelled->second;
        return;
      }
  }
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
    if (HeldFolder& entry = held[key]; entry.holders > 0 && entry.sharedWith(std::this_thread::get_id())) {
      ++entry.holders;  // this thread holds it already, or was given it: share it
      ::close(fd);
      key_ = key;
      return;
    }
  }
  // Free, or held by another thread that did not share it: flock on this
  // descriptor waits for (or refuses) that holder as for another process.
  // Not under the mutex: waiting for another process must not stop this
  // one's other folders.
  try {
    flockOrThrow(fd, folder, wait, waitSeconds, waiting);
  } catch (...) {
    const std::lock_guard guard(heldMutex);
    if (held[key].holders == 0) held.erase(key);
    throw;
  }
  const std::lock_guard guard(heldMutex);
  HeldFolder& entry = held[key];  // the flock is ours, so no other holder is left
  entry.fd = fd;
  entry.owner = std::this_thread::get_id();
  ++entry.holders;
  key_ = key;
  heldSpellings[spelling(folder)] = key;
}

std::filesystem::path OutputFolderLock::directory() const {
  const std::lock_guard guard(heldMutex);
  return "/proc/self/fd/" + std::to_string(held.at(key_).fd);
}

std::string OutputFolderLock::named(std::string text, const std::filesystem::path& name) const {
  const std::string through = directory().string(), spelled = name.string();
  for (std::size_t at = text.find(through); at != std::string::npos; at = text.find(through, at + spelled.size()))
    text.replace(at, through.size(), spelled);
  return text;
}

OutputFolderLock::ThreadShare::ThreadShare(const OutputFolderLock& lock) : key_(lock.key_) {
  const std::lock_guard guard(heldMutex);
  held[key_].sharers.insert(std::this_thread::get_id());
}

OutputFolderLock::ThreadShare::~ThreadShare() {
  const std::lock_guard guard(heldMutex);
  if (auto found = held.find(key_); found != held.end()) {
    auto& sharers = found->second.sharers;
    if (auto mine = sharers.find(std::this_thread::get_id()); mine != sharers.end()) sharers.erase(mine);
  }
}

OutputFolderLock::~OutputFolderLock() {
  const std::lock_guard guard(heldMutex);
  auto found = held.find(key_);
  if (found == held.end() || --found->second.holders > 0) return;
  // Only the folder this lock made, if its name still names it.
  if (created_ && stillNames(folder_, key_)) {
    std::error_code ignored;
    if (fs::is_empty(folder_, ignored) && !ignored) fs::remove(folder_, ignored);
  }
  ::close(found->second.fd);  // closing drops the flock
  held.erase(found);
  for (auto it = heldSpellings.begin(); it != heldSpellings.end();)
    it = it->second == key_ ? heldSpellings.erase(it) : std::next(it);
}

}  // namespace headlight::detail
