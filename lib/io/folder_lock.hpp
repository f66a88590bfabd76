#pragma once
// An advisory lock on an output folder: two renders into one folder would
// otherwise interleave their files into a set neither wrote. flock(2) on
// the folder itself (its directory descriptor: no lock file joins the set),
// held from before the render until its set is written; the kernel drops it
// when the process dies, so a killed render never leaves the folder locked.
// Advisory: only Headlight processes (and anything else that flocks the
// folder) honour it; a network file system without flock may not.
//
// The lock is the folder, not its name: a thread that locked `out` and
// takes `out` again gets the same folder, whatever `out` names now, and
// writes into it through directory().
//
// Within one process a lock is shared only where its holder allows: the
// thread that took it may take it again (the CLI holds a folder's lock from
// before the render, and writeFrame takes it again), and so may a thread
// the holder shares it with (ThreadShare: the batch's writer thread). The
// flock is dropped with the last of them. Any other thread of the process
// (two Python threads calling Frame.write into one folder) takes the flock
// through a descriptor of its own, which flock keeps apart as it keeps
// processes apart: it waits, or is refused, like another process.
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

  // The locked folder itself, as a path through its descriptor
  // (/proc/self/fd/N): files written under it land in the folder the lock
  // holds even when its name was moved meanwhile (`mv out out.old; mkdir
  // out` while a render runs), where the name would send them elsewhere.
  std::filesystem::path directory() const;
  // `text` (a message, a file's summary) with directory() spelled as `name`,
  // the folder's name as the caller gave it.
  std::string named(std::string text, const std::filesystem::path& name) const;

  // While it lives, the thread that makes it may take `lock`'s folder
  // again, sharing the lock (made on that thread; `lock` must outlive it).
  class ThreadShare {
   public:
    explicit ThreadShare(const OutputFolderLock& lock);
    ~ThreadShare();
    ThreadShare(const ThreadShare&) = delete;
    ThreadShare& operator=(const ThreadShare&) = delete;

   private:
    std::string key_;
  };

 private:
  std::filesystem::path folder_;
  std::string key_;  // the folder's device and inode: one entry per folder however it is spelled
  bool created_ = false;
};

}  // namespace headlight::detail
