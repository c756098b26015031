// Atomic output: temporary file in the target directory, checked writes, fsync, rename.
#include "common/atomic_file.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
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

void make_durable(const std::vector<std::string>& paths, const std::string& directory) {
  for (const std::string& path : paths) {
    const int fd = ::open(path.c_str(), O_RDONLY);
    if (fd < 0 || ::fsync(fd) != 0) {
      const std::string why = std::strerror(errno);
      if (fd >= 0) ::close(fd);
      throw InputError(path + ": cannot write the file to disk (" + why + ")");
    }
    ::close(fd);
  }
  if (!paths.empty()) sync_directory(directory);
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
