// The output directory of a stage (mppm-solve's run directory, mppm-postprocess's post
// directory) is never overwritten silently: an existing non-empty directory is refused unless
// the user passes --force, and --force replaces it as a whole, so no file of the earlier output
// (a snapshot or frame the new run does not write) can be mistaken for part of the new one.
#pragma once
#include <string>
#include <vector>

namespace mppm {

struct OutputDirectoryKind {
  std::string what;    // "run directory", "post directory": for the messages
  std::string option;  // the command-line option that names it, e.g. "-o RUN_DIR"
  // Names of which at least one exists in an earlier output of this stage. --force deletes
  // only a directory that has one, never e.g. a home directory given to -o by mistake.
  std::vector<std::string> markers;
};

// Makes `directory` an empty, existing directory. A missing or empty directory is created or
// kept; a non-empty one throws InputError (naming the directory and --force) unless `force`;
// with `force`, a directory with one of `kind.markers` is deleted and created again, any other
// throws InputError. Also throws InputError when the directory cannot be created or removed.
void prepare_output_directory(const std::string& directory, bool force, const OutputDirectoryKind& kind);

}  // namespace mppm
