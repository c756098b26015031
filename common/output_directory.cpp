// Refusal or clean replacement of an existing output directory (see output_directory.hpp).
#include "common/output_directory.hpp"

#include <unistd.h>

#include <filesystem>
#include <iostream>
#include <system_error>
#include <utility>

#include "common/input_error.hpp"

namespace mppm {

namespace fs = std::filesystem;

namespace {

// Why deleting `path` failed, or "".
std::string remove_tree(const std::string& path) {
  std::error_code ec;
  fs::remove_all(path, ec);
  return ec ? ec.message() : std::string();
}

// remove_tree(path) on a thread of its own, or here when no thread can be started.
std::future<std::string> start_removal(const std::string& path) {
  try {
    return std::async(std::launch::async, remove_tree, path);
  } catch (const std::system_error&) {
    std::promise<std::string> done;
    done.set_value(remove_tree(path));
    return done.get_future();
  }
}

}  // namespace

EarlierOutputRemoval::EarlierOutputRemoval(std::string aside, std::string what)
    : aside_(std::move(aside)), what_(std::move(what)), failure_(start_removal(aside_)) {}

std::string EarlierOutputRemoval::wait() { return failure_.valid() ? failure_.get() : std::string(); }

EarlierOutputRemoval::~EarlierOutputRemoval() {
  const std::string why = wait();
  if (!why.empty())
    std::cerr << "warning: cannot remove the earlier " << what_ << ", moved to " << aside_ << " (" << why
              << "); delete it by hand\n";
}

namespace {

// A non-empty `dir` with one of the stage's files moved aside (with `force`) and its deletion
// started; refused otherwise (InputError).
EarlierOutputRemoval move_earlier_output_aside(const fs::path& dir, const std::string& directory, bool force,
                                               const OutputDirectoryKind& kind) {
  std::error_code ec;
  if (!fs::exists(dir, ec)) return {};
  if (!fs::is_directory(dir, ec))
    throw InputError(directory + ": exists and is not a directory (expected the " + kind.what + " to create)");
  if (fs::is_empty(dir, ec)) return {};
  if (!force)
    throw InputError(directory + ": the " + kind.what +
                     " already exists and is not empty; use --force to replace it, or choose another " + kind.option);
  bool earlier_output = false;
  for (const std::string& marker : kind.markers) earlier_output = earlier_output || fs::exists(dir / marker, ec);
  if (!earlier_output)
    throw InputError(directory +
                     ": not replaced although --force was given: it is not empty and does not look like a " +
                     kind.what + " (none of its files is there); choose another " + kind.option);
  // Renamed aside first so that the old output disappears at once: a failure below never
  // leaves a half-deleted mix of old files under the directory's name.
  fs::path aside = dir;
  aside += ".replaced-" + std::to_string(::getpid());
  fs::remove_all(aside, ec);
  fs::rename(dir, aside, ec);
  if (ec) throw InputError(directory + ": cannot replace the " + kind.what + " (" + ec.message() + ")");
  return EarlierOutputRemoval(aside.string(), kind.what);
}

}  // namespace

EarlierOutputRemoval prepare_output_directory(const std::string& directory, bool force,
                                              const OutputDirectoryKind& kind) {
  // "out/run/" and "out/run" are the same directory; the trailing separator would put the
  // renamed-aside copy below inside the directory itself.
  fs::path dir = fs::path(directory).lexically_normal();
  if (!dir.has_filename() && dir.has_parent_path()) dir = dir.parent_path();
  EarlierOutputRemoval earlier = move_earlier_output_aside(dir, directory, force, kind);
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw InputError(directory + ": cannot create the " + kind.what + " (" + ec.message() + ")");
  return earlier;
}

}  // namespace mppm
