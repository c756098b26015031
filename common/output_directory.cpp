// Refusal or clean replacement of an existing output directory (see output_directory.hpp).
#include "common/output_directory.hpp"

#include <unistd.h>

#include <filesystem>
#include <system_error>

#include "common/input_error.hpp"

namespace mppm {

namespace fs = std::filesystem;

void prepare_output_directory(const std::string& directory, bool force, const OutputDirectoryKind& kind) {
  std::error_code ec;
  // "out/run/" and "out/run" are the same directory; the trailing separator would put the
  // renamed-aside copy below inside the directory itself.
  fs::path dir = fs::path(directory).lexically_normal();
  if (!dir.has_filename() && dir.has_parent_path()) dir = dir.parent_path();
  if (fs::exists(dir, ec)) {
    if (!fs::is_directory(dir, ec))
      throw InputError(directory + ": exists and is not a directory (expected the " + kind.what + " to create)");
    if (!fs::is_empty(dir, ec)) {
      if (!force)
        throw InputError(directory + ": the " + kind.what +
                         " already exists and is not empty; use --force to replace it, or choose another " +
                         kind.option);
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
      fs::remove_all(aside, ec);
      if (ec)
        throw InputError(directory + ": cannot remove the earlier " + kind.what + " (moved to " + aside.string() +
                         "): " + ec.message());
    }
  }
  fs::create_directories(dir, ec);
  if (ec) throw InputError(directory + ": cannot create the " + kind.what + " (" + ec.message() + ")");
}

}  // namespace mppm
