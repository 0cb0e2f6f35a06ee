#include "io/atomic_file.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>

#include "core/error.hpp"

namespace cgdem::io {
namespace {

std::string errno_text() { return std::strerror(errno); }

// fsync a file or directory by name; `what` is for the error message.
void fsync_path(const std::string& p, bool directory) {
  int fd = ::open(p.c_str(), directory ? (O_RDONLY | O_DIRECTORY) : O_RDONLY);
  if (fd < 0) throw Error("cannot open '" + p + "' for fsync: " + errno_text());
  int rc = ::fsync(fd);
  int err = errno;
  ::close(fd);
  // Some file systems refuse fsync on directories (EINVAL); the rename is still atomic.
  if (rc != 0 && !(directory && (err == EINVAL || err == EBADF)))
    throw Error("fsync of '" + p + "' failed: " + std::strerror(err));
}

std::string parent_dir(const std::string& path) {
  std::filesystem::path parent = std::filesystem::path(path).parent_path();
  return parent.empty() ? std::string(".") : parent.string();
}

}  // namespace

std::string temporary_path(const std::string& path) {
  if (path.empty()) throw Error("output file name is empty");
  return path + ".tmp-" + std::to_string(::getpid());
}

void commit_temporary(const std::string& tmp, const std::string& path) {
  try {
    fsync_path(tmp, false);  // a full disk may first show here (delayed allocation)
    if (std::rename(tmp.c_str(), path.c_str()) != 0)
      throw Error("cannot rename '" + tmp + "' to '" + path + "': " + errno_text());
  } catch (const Error& e) {
    std::remove(tmp.c_str());
    throw Error("cannot write '" + path + "': " + e.what() + " (the previous file is unchanged)");
  }
  fsync_path(parent_dir(path), true);
}

void write_file_atomic(const std::string& path, std::string_view bytes) {
  const std::string tmp = temporary_path(path);
  int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) throw Error("cannot write '" + path + "': cannot create its temporary '" + tmp + "': " + errno_text());
  size_t done = 0;
  while (done < bytes.size()) {
    ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) {
      // EFBIG (file-size limit), ENOSPC (disk full), EIO: the previous `path` stays as it was
      std::string msg = "cannot write '" + path + "': " + errno_text() + " (after " + std::to_string(done) + " of " +
                        std::to_string(bytes.size()) + " bytes to its temporary '" + tmp +
                        "'; the previous file is unchanged)";
      ::close(fd);
      std::remove(tmp.c_str());
      throw Error(msg);
    }
    done += static_cast<size_t>(n);
  }
  if (::close(fd) != 0) {
    std::string msg = "cannot write '" + path + "': closing its temporary '" + tmp + "' failed: " + errno_text();
    std::remove(tmp.c_str());
    throw Error(msg);
  }
  commit_temporary(tmp, path);
}

AtomicTarget::AtomicTarget(std::string path) : path_(std::move(path)), tmp_(temporary_path(path_)) {
  std::remove(tmp_.c_str());  // a stale temporary from a crashed run with the same pid
}

AtomicTarget::~AtomicTarget() {
  if (!committed_) std::remove(tmp_.c_str());
}

void AtomicTarget::commit() {
  if (committed_) throw Error("'" + path_ + "' committed twice");
  committed_ = true;  // commit_temporary removes the temporary itself on failure
  commit_temporary(tmp_, path_);
}

}  // namespace cgdem::io
