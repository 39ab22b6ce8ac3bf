#include "rgraph/output_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <optional>

#include "rgraph/error.h"

namespace rgraph {
namespace fs = std::filesystem;

namespace {

std::string reason(int err) { return std::strerror(err); }

[[noreturn]] void fail(const std::string& what, const std::string& path, const std::string& why) {
  throw RuntimeError("cannot write " + what + " " + path + ": " + why);
}

std::optional<struct stat> statOf(const std::string& path, int& err) {
  struct stat st {};
  if (::stat(path.c_str(), &st) == 0) return st;
  err = errno;
  return std::nullopt;
}

// Writes all of `bytes` to fd; 0 or the errno of the failed write.
int writeAll(int fd, std::string_view bytes) {
  while (!bytes.empty()) {
    const ssize_t n = ::write(fd, bytes.data(), bytes.size());
    if (n < 0) {
      if (errno == EINTR) continue;
      return errno;
    }
    if (n == 0) return EIO;
    bytes.remove_prefix(static_cast<size_t>(n));
  }
  return 0;
}

// Opens `path` with `flags`, writes, closes: 0 or the first errno.
int writeThrough(const std::string& path, int flags, std::string_view bytes) {
  const int fd = ::open(path.c_str(), flags | O_WRONLY | O_CLOEXEC | O_NOCTTY, 0666);
  if (fd < 0) return errno;
  int err = writeAll(fd, bytes);
  if (::close(fd) != 0 && err == 0) err = errno;
  return err;
}

// A new file beside `target` that no other writer uses; -1 with errno set when none can be made.
int createTemporary(const fs::path& target, std::string& tmp) {
  static std::atomic<unsigned> counter{0};
  for (int attempt = 0; attempt < 100; ++attempt) {
    tmp = (target.parent_path() / ("." + target.filename().string() + ".rgraph-tmp." + std::to_string(::getpid()) +
                                   "." + std::to_string(counter++)))
              .string();
    const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (fd >= 0 || errno != EEXIST) return fd;
  }
  return -1;
}

// The temporary-and-rename write of a regular (or new) file at `target`
// (links already followed): 0 or the errno of the step that failed.
int replaceFile(const std::string& target, std::string_view bytes) {
  int err = 0;
  std::optional<struct stat> old = statOf(target, err);
  std::string tmp;
  const int fd = createTemporary(target, tmp);
  if (fd < 0) return errno;
  err = writeAll(fd, bytes);
  if (err == 0 && old) ::fchmod(fd, old->st_mode & 07777);  // best effort: the content matters, not the mode
  if (err == 0 && ::fsync(fd) != 0 && errno != EINVAL) err = errno;  // EINVAL: a file system without fsync
  if (::close(fd) != 0 && err == 0) err = errno;
  if (err == 0 && ::rename(tmp.c_str(), target.c_str()) != 0) err = errno;
  if (err != 0) ::unlink(tmp.c_str());
  return err;
}

// Follows the symbolic links `path` ends in (dangling ones included); the
// final name is not a link. nullopt with err set on a loop or unreadable link.
std::optional<fs::path> followLinks(const std::string& path, int& err) {
  std::error_code ec;
  fs::path p = fs::absolute(path, ec);
  if (ec) {
    err = ec.value();
    return std::nullopt;
  }
  for (int hops = 0; hops < 40; ++hops) {
    struct stat st {};
    if (::lstat(p.c_str(), &st) != 0 || !S_ISLNK(st.st_mode)) return p;
    const fs::path link = fs::read_symlink(p, ec);
    if (ec) {
      err = ec.value();
      return std::nullopt;
    }
    p = link.is_absolute() ? link : p.parent_path() / link;
  }
  err = ELOOP;
  return std::nullopt;
}

// Where the bytes of a new or regular file at `path` go; nullopt with err set when that cannot be told.
std::optional<std::string> replaceTarget(const std::string& path, int& err) {
  std::optional<fs::path> p = followLinks(path, err);
  if (!p) return std::nullopt;
  std::error_code ec;
  const fs::path dir = fs::weakly_canonical(p->parent_path(), ec);
  if (ec) {
    err = ec.value();
    return std::nullopt;
  }
  return (dir / p->filename()).string();
}

}  // namespace

std::string outputFileTarget(const std::string& path) {
  int err = 0;
  return replaceTarget(path, err).value_or("");
}

void writeOutputFile(const std::string& path, std::string_view bytes, const std::string& what) {
  if (const std::string problem = outputFileProblem(path); !problem.empty()) fail(what, path, problem);
  int err = 0;
  std::optional<struct stat> st = statOf(path, err);
  if (st && !S_ISREG(st->st_mode)) {
    err = writeThrough(path, 0, bytes);
  } else {
    std::optional<std::string> target = replaceTarget(path, err);
    if (target) err = replaceFile(*target, bytes);
  }
  if (err != 0) fail(what, path, reason(err));
}

void appendToFile(const std::string& path, std::string_view bytes, const std::string& what) {
  const int err = writeThrough(path, O_APPEND | O_CREAT, bytes);
  if (err != 0) fail(what, path, reason(err));
}

std::string outputFileProblem(const std::string& path) {
  if (path.empty()) return "no file name given";
  if (fs::path(path).filename().empty() || fs::path(path).filename() == "." || fs::path(path).filename() == "..")
    return "names a folder, not a file";
  int err = 0;
  if (std::optional<struct stat> st = statOf(path, err)) {
    if (S_ISDIR(st->st_mode)) return "is a folder";
    // A file the user made read-only stays so, although the rename could replace it.
    if (::access(path.c_str(), W_OK) != 0) return reason(errno);
    if (!S_ISREG(st->st_mode)) return "";  // written in place
  } else if (err != ENOENT) {
    return reason(err);
  }
  std::optional<std::string> target = replaceTarget(path, err);
  if (!target) return reason(err);
  const fs::path dir = fs::path(*target).parent_path();
  std::optional<struct stat> dirSt = statOf(dir.string(), err);
  if (!dirSt) return err == ENOENT ? "no such folder '" + dir.string() + "'" : reason(err);
  if (!S_ISDIR(dirSt->st_mode)) return "'" + dir.string() + "' is not a folder";
  std::string probe;
  const int fd = createTemporary(*target, probe);
  if (fd < 0) return reason(errno) + " (in '" + dir.string() + "')";
  ::close(fd);
  ::unlink(probe.c_str());
  return "";
}

}  // namespace rgraph
