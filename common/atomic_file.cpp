// Atomic output: temporary file in the target directory, checked writes, fsync, rename.
#include "common/atomic_file.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstddef>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "common/input_error.hpp"

namespace mppm {

std::string temporary_name_for(const std::string& path) {
  const std::filesystem::path p(path);
  // Built by appending: GCC 12 warns falsely (-Wrestrict, PR105329) on "." + std::string.
  std::string name(1, '.');
  name += p.filename().string();
  name += ".tmp-";
  name += std::to_string(::getpid());
  return (p.parent_path() / name).string();
}

namespace {

[[noreturn]] void fail_and_remove(const std::string& temporary, const std::string& path, const std::string& why) {
  std::error_code ignored;
  std::filesystem::remove(temporary, ignored);
  throw InputError(path + ": cannot write the file (" + why + ")");
}

// The rename is durable only once the directory entry is on disk. Best effort: some file
// systems cannot fsync a directory, and the files themselves are already complete either way.
void sync_directory(const std::string& directory) {
  const int dir_fd = ::open(directory.empty() ? "." : directory.c_str(), O_RDONLY | O_DIRECTORY);
  if (dir_fd >= 0) {
    (void)::fsync(dir_fd);
    ::close(dir_fd);
  }
}

std::string parent_of(const std::string& path) { return std::filesystem::path(path).parent_path().string(); }

}  // namespace

void commit_temporary(const std::string& temporary, const std::string& path) {
  // fsync the data before the rename so a crash never exposes an empty file under `path`.
  const int fd = ::open(temporary.c_str(), O_RDONLY);
  if (fd < 0 || ::fsync(fd) != 0) {
    const std::string why = std::strerror(errno);
    if (fd >= 0) ::close(fd);
    fail_and_remove(temporary, path, why);
  }
  ::close(fd);
  rename_temporary(temporary, path);
  sync_directory(parent_of(path));
}

void rename_temporary(const std::string& temporary, const std::string& path) {
  if (std::rename(temporary.c_str(), path.c_str()) != 0) fail_and_remove(temporary, path, std::strerror(errno));
}

namespace {

// fsyncs the files as one batch (StagedFiles::commit), with `names[k]` the file a failure of
// `paths[k]` is reported as (a temporary is reported as the file it stands for).
void sync_named_files(const std::vector<std::string>& paths, const std::vector<std::string>& names) {
  // Best effort: a file that cannot be opened here fails its fsync below, with the reason.
  for (const std::string& path : paths) {
    const int fd = ::open(path.c_str(), O_RDONLY);
    if (fd < 0) continue;
    (void)::sync_file_range(fd, 0, 0, SYNC_FILE_RANGE_WRITE);
    ::close(fd);
  }
  for (std::size_t k = 0; k < paths.size(); ++k) {
    const int fd = ::open(paths[k].c_str(), O_RDONLY);
    if (fd < 0 || ::fsync(fd) != 0) {
      const std::string why = std::strerror(errno);
      if (fd >= 0) ::close(fd);
      throw InputError(names[k] + ": cannot write the file to disk (" + why + ")");
    }
    ::close(fd);
  }
}

}  // namespace

StagedFiles::~StagedFiles() {
  std::error_code ignored;
  for (const Staged& s : staged_) std::filesystem::remove(s.temporary, ignored);
}

void StagedFiles::stage(const std::string& path, const std::function<void(std::ostream&)>& write) {
  staged_.push_back(Staged{write_temporary(path, write), path});
}

void StagedFiles::commit(const std::vector<std::string>& also_durable,
                         const std::vector<std::string>& also_directories) {
  std::vector<std::string> files = also_durable, names = also_durable;
  for (const Staged& s : staged_) {
    files.push_back(s.temporary);
    names.push_back(s.path);
  }
  sync_named_files(files, names);
  for (const std::string& d : also_directories) sync_directory(d);
  const std::vector<Staged> to_rename = std::move(staged_);
  staged_.clear();
  for (std::size_t k = 0; k < to_rename.size(); ++k) {
    // Every file before the last is on disk under its name before the last is renamed.
    if (k + 1 == to_rename.size() && k > 0) sync_directory(parent_of(to_rename[k].path));
    try {
      rename_temporary(to_rename[k].temporary, to_rename[k].path);
    } catch (...) {
      staged_.assign(to_rename.begin() + static_cast<std::ptrdiff_t>(k) + 1,
                     to_rename.end());  // removed by ~StagedFiles
      throw;
    }
  }
  if (!to_rename.empty()) sync_directory(parent_of(to_rename.back().path));
}

std::string write_temporary(const std::string& path, const std::function<void(std::ostream&)>& write) {
  const std::string temporary = temporary_name_for(path);
  {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    if (!out) {
      throw InputError(path + ": cannot create the file (" + std::string(std::strerror(errno)) + ")");
    }
    std::error_code ignored;
    try {
      write(out);
    } catch (...) {
      out.close();
      std::filesystem::remove(temporary, ignored);
      throw;
    }
    // A failed write sets the stream state; errno still tells why. close() flushes the last
    // buffer, and its failure (disk full, file size limit) must count too.
    int error = out ? 0 : errno;
    if (out) {
      errno = 0;
      out.close();
      if (!out) error = errno;
    }
    if (!out) {
      const std::string why = error ? std::strerror(error) : "write error";
      out.close();
      std::filesystem::remove(temporary, ignored);
      throw InputError(path + ": writing failed (" + why +
                       "; is the disk full?); the previous file, if any, is unchanged");
    }
  }
  return temporary;
}

void write_file_atomically(const std::string& path, const std::function<void(std::ostream&)>& write) {
  commit_temporary(write_temporary(path, write), path);
}

}  // namespace mppm
