// The output directory of a stage (mppm-solve's run directory, mppm-postprocess's post
// directory) is never overwritten silently: an existing non-empty directory is refused unless
// the user passes --force, and --force replaces it as a whole, so no file of the earlier output
// (a snapshot or frame the new run does not write) can be mistaken for part of the new one.
#pragma once
#include <future>
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

// The earlier output that --force replaced: renamed aside at once (to DIR.replaced-PID, so that
// none of it is under the directory's name any more) and deleted on a thread of its own, beside
// the stage, which need not wait for the disk (deleting a run directory took 8-15 ms of the
// crack-branching plate's start-up, and once 280 ms, against 1 ms for a new directory). The
// destructor waits for the deletion; a failure is then reported on stderr, naming the directory
// left behind (the new output is complete either way).
class EarlierOutputRemoval {
 public:
  EarlierOutputRemoval() = default;  // nothing to remove
  EarlierOutputRemoval(std::string aside, std::string what);
  EarlierOutputRemoval(EarlierOutputRemoval&&) = default;
  EarlierOutputRemoval& operator=(EarlierOutputRemoval&&) = delete;
  ~EarlierOutputRemoval();
  // Waits for the deletion; returns why it failed ("" when it did not, or there was none).
  std::string wait();

 private:
  std::string aside_, what_;
  std::future<std::string> failure_;
};

// Makes `directory` an empty, existing directory. A missing or empty directory is created or
// kept; a non-empty one throws InputError (naming the directory and --force) unless `force`;
// with `force`, a directory with one of `kind.markers` is replaced by an empty one (its deletion
// is the returned object's: keep it while the stage runs), any other throws InputError. Also
// throws InputError when the directory cannot be created or moved aside.
[[nodiscard]] EarlierOutputRemoval prepare_output_directory(const std::string& directory, bool force,
                                                            const OutputDirectoryKind& kind);

}  // namespace mppm
