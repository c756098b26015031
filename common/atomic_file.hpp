// Output files are written to a temporary name in the same directory, flushed, and renamed,
// so no stage ever leaves a half-written file under its final name.
#pragma once
#include <functional>
#include <ostream>
#include <string>

namespace mppm {

// Calls `write(stream)` on a temporary file next to `path`, checks every write, fsyncs and
// renames it to `path`. Throws InputError (naming `path` and the OS error) on failure and
// removes the temporary.
void write_file_atomically(const std::string& path, const std::function<void(std::ostream&)>& write);

// The first half of write_file_atomically: writes the temporary next to `path` and returns its
// name, for commit_temporary (which may run later, on another thread: its fsyncs wait for the
// disk). Throws InputError as write_file_atomically does, with the temporary removed.
std::string write_temporary(const std::string& path, const std::function<void(std::ostream&)>& write);

// Temporary name used for `path` (same directory, so the rename is atomic).
std::string temporary_name_for(const std::string& path);

// Renames `temporary` onto `path` after fsync; throws InputError on failure.
void commit_temporary(const std::string& temporary, const std::string& path);

}  // namespace mppm
