#include "retarget/run/output_folder.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <random>

#include <fmt/format.h>

#include "core/common/errors.hpp"

namespace gr {

namespace fs = std::filesystem;

namespace {

/// Whether `path` is `folder` or lies inside it (both absolute and normalized).
bool lies_inside(const fs::path& path, const fs::path& folder) {
  auto p = path.begin();
  for (auto f = folder.begin(); f != folder.end(); ++f, ++p) {
    if (f->empty()) continue;  // a trailing separator
    if (p == path.end() || *p != *f) return false;
  }
  return true;
}

fs::path resolved(const fs::path& path) {
  std::error_code ec;
  fs::path canonical = fs::weakly_canonical(fs::absolute(path), ec);
  return ec ? fs::absolute(path).lexically_normal() : canonical;
}

/// Opens and locks `path` without waiting; -1 when another process holds it. The file is
/// checked to be the one at `path` after locking: a holder that released it may have
/// removed it meanwhile.
int lock_file(const fs::path& path) {
  for (;;) {
    const int fd = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (fd < 0)
      throw OutputError(
          fmt::format("{}: cannot create lock file: {}", path.string(), std::strerror(errno)));
    if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
      const int error = errno;
      ::close(fd);
      if (error == EWOULDBLOCK) return -1;
      throw OutputError(fmt::format("{}: cannot lock: {}", path.string(), std::strerror(error)));
    }
    struct stat locked {
    }, named{};
    if (::fstat(fd, &locked) == 0 && ::stat(path.c_str(), &named) == 0 &&
        locked.st_ino == named.st_ino && locked.st_dev == named.st_dev)
      return fd;
    ::close(fd);
  }
}

}  // namespace

void prepare_output_folder(const std::string& out_dir) {
  std::error_code ec;
  fs::create_directories(out_dir, ec);
  if (ec || !fs::is_directory(out_dir))
    throw OutputError(out_dir + ": cannot create output folder" +
                      (ec ? ": " + ec.message() : std::string()));
}

bool exchange_folders(const fs::path& folder, const fs::path& destination) {
  const auto fail = [&]() {
    return OutputError(fmt::format("{}: cannot move the outputs into place: {}",
                                   destination.string(), std::strerror(errno)));
  };
  if (::renameat2(AT_FDCWD, folder.c_str(), AT_FDCWD, destination.c_str(), RENAME_EXCHANGE) == 0)
    return true;
  if (errno == ENOENT) {
    if (std::rename(folder.c_str(), destination.c_str()) != 0) throw fail();
    return false;
  }
  if (errno != EINVAL && errno != ENOSYS) throw fail();
  const fs::path aside = folder.string() + "-old";
  if (std::rename(destination.c_str(), aside.c_str()) != 0) throw fail();
  if (std::rename(folder.c_str(), destination.c_str()) != 0) throw fail();
  if (std::rename(aside.c_str(), folder.c_str()) != 0) throw fail();
  return true;
}

StagedFiles::~StagedFiles() {
  if (committed_) return;
  std::error_code ignored;
  for (const auto& [staging, target] : files_) fs::remove(staging, ignored);
}

std::string StagedFiles::stage(const std::string& target) {
  const fs::path path(target);
  const fs::path folder = path.has_parent_path() ? path.parent_path() : fs::path(".");
  std::error_code ec;
  if (!fs::is_directory(folder, ec))
    throw OutputError(
        fmt::format("{}: output folder '{}' does not exist", target, folder.string()));
  std::random_device entropy;
  const fs::path staging =
      path.parent_path() /
      fmt::format(".{}.staged-{}-{:08x}", path.filename().string(), ::getpid(), entropy());
  files_.emplace_back(staging.string(), target);
  return staging.string();
}

void StagedFiles::commit() {
  for (const auto& [staging, target] : files_)
    if (std::rename(staging.c_str(), target.c_str()) != 0)
      throw OutputError(
          fmt::format("{}: cannot move the output into place: {}", target, std::strerror(errno)));
  committed_ = true;
}

ResultFolder::ResultFolder(const std::string& out_dir, const std::vector<std::string>& inputs,
                           bool in_place)
    : destination_(out_dir), in_place_(in_place) {
  if (out_dir.empty()) throw InputError("", 0, "no output folder given (--out)");
  absolute_ = fs::absolute(out_dir).lexically_normal();
  if (absolute_.filename().empty()) absolute_ = absolute_.parent_path();
  const std::string name = absolute_.filename().string();
  if (name.empty() || name == "." || name == ".." || absolute_ == absolute_.root_path())
    throw InputError(out_dir, 0, "cannot write a result folder here: name a folder of its own");
  const fs::path dir = resolved(absolute_);
  for (const std::string& input : inputs)
    if (!input.empty() && lies_inside(resolved(input), dir))
      throw InputError(out_dir, 0,
                       fmt::format("the output folder holds the input {}; a run replaces its "
                                   "output folder as a whole: choose another --out",
                                   input));
  if (in_place_) {
    prepare_output_folder(out_dir);
    staging_ = destination_;
    return;
  }

  const fs::path parent = absolute_.parent_path();
  std::error_code ec;
  fs::create_directories(parent, ec);
  if (ec || !fs::is_directory(parent))
    throw OutputError(fmt::format("{}: cannot create output folder{}", out_dir,
                                  ec ? ": " + ec.message() : std::string()));
  lock_path_ = parent / ("." + name + ".lock");
  lock_fd_ = lock_file(lock_path_);
  if (lock_fd_ < 0)
    throw OutputError(fmt::format("{}: another run is writing this folder now (lock {})", out_dir,
                                  lock_path_.string()));

  if (fs::exists(absolute_, ec)) {
    if (!fs::is_directory(absolute_, ec))
      throw InputError(out_dir, 0, "the output path exists and is not a folder");
    const bool empty = fs::is_empty(absolute_, ec);
    if (!empty && !fs::is_regular_file(absolute_ / "report.json", ec))
      throw InputError(out_dir, 0,
                       "the output folder holds files but no report.json, so it is not a "
                       "result folder, which a run replaces as a whole: choose a new or empty "
                       "folder");
    has_previous_ = !empty;
  }

  // Staging folders of runs into DIR that were killed: the lock says none is running.
  const std::string staging_prefix = "." + name + ".tmp-";
  for (const auto& entry : fs::directory_iterator(parent, ec))
    if (entry.path().filename().string().rfind(staging_prefix, 0) == 0)
      fs::remove_all(entry.path(), ec);

  std::random_device entropy;
  staging_ = parent / fmt::format("{}{}-{:08x}", staging_prefix, ::getpid(), entropy());
  if (!fs::create_directory(staging_, ec) || ec)
    throw OutputError(fmt::format("{}: cannot create a staging folder beside it: {}", out_dir,
                                  ec ? ec.message() : "it exists"));
}

ResultFolder::~ResultFolder() {
  std::error_code ignored;
  if (!in_place_ && !committed_ && !staging_.empty()) fs::remove_all(staging_, ignored);
  if (lock_fd_ >= 0) {
    ::unlink(lock_path_.c_str());
    ::close(lock_fd_);
  }
}

std::string ResultFolder::final_path(const std::string& name) const {
  return (destination_ / name).string();
}

std::string ResultFolder::previous_path() const {
  return (absolute_.parent_path() / (absolute_.filename().string() + ".previous")).string();
}

void ResultFolder::commit(bool keep_previous) {
  if (in_place_ || committed_) {
    committed_ = true;
    return;
  }
  const bool exchanged = exchange_folders(staging_, absolute_);
  committed_ = true;
  if (!exchanged) return;
  std::error_code ec;
  if (keep_previous && has_previous_) {
    const fs::path previous = previous_path();
    fs::remove_all(previous, ec);
    fs::rename(staging_, previous, ec);
    if (!ec) return;
  }
  fs::remove_all(staging_, ec);
}

}  // namespace gr
