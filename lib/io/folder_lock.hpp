#pragma once
// An advisory lock on an output folder: two renders into one folder would
// otherwise interleave their files into a set neither wrote. flock(2) on
// the folder itself (its directory descriptor: no lock file joins the set),
// held from before the render until its set is written; the kernel drops it
// when the process dies, so a killed render never leaves the folder locked.
// Advisory: only Headlight processes (and anything else that flocks the
// folder) honour it; a network file system without flock may not.
//
// Within one process the lock is shared: the CLI holds a folder's lock from
// before the render, and writeFrame (which every embedder calls) takes it
// again on its writer thread. flock would make that second taking wait for
// the first forever, so a process-wide count per folder lets a nested lock
// through; the flock is dropped with the last one. Two threads of one
// process writing one folder at once are therefore not kept apart.
#include <filesystem>
#include <functional>
#include <string>

namespace headlight::detail {

// How long a render waits for another's folder unless told: a holder that
// stopped (a suspended job, a stuck mount, `flock` in a shell) is not
// waited for forever.
inline constexpr double kDefaultWaitSeconds = 600.0;

// Who holds the flock on the folder `fd` is open on, from /proc/locks: "process
// 1234 (headlight)"; "another process" where the table cannot tell.
std::string folderLockHolder(int fd);

class OutputFolderLock {
 public:
  // Creates `folder` if needed and takes the lock. With `wait` false, a
  // folder another process holds is an IoError at once, naming the folder,
  // the process that holds it and the `wait` setting; with `wait` true, it
  // waits up to `waitSeconds` for the folder, calling `waiting` once with
  // the holder's description first, and is then an IoError naming the
  // holder and the time waited.
  OutputFolderLock(const std::filesystem::path& folder, bool wait, double waitSeconds = kDefaultWaitSeconds,
                   const std::function<void(const std::string& holder)>& waiting = {});
  // Drops the lock; a folder this lock created and nothing was written
  // into (the render failed) is removed again, as if never touched.
  ~OutputFolderLock();
  OutputFolderLock(const OutputFolderLock&) = delete;
  OutputFolderLock& operator=(const OutputFolderLock&) = delete;

 private:
  std::filesystem::path folder_;
  std::string key_;  // the folder's device and inode: one entry per folder however it is spelled
  bool created_ = false;
};

}  // namespace headlight::detail
