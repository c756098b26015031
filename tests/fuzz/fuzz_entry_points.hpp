// The entry points that the libFuzzer targets and the corpus test (test_reliability_corpus)
// feed with untrusted input, plus the contract each one enforces. Shared so that a crash
// reproducer found by a fuzzer is replayed through exactly the same code in the normal build.
#pragma once
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace mppm::fuzz {

// What an input did: accepted, or rejected with this message (an InputError for files,
// std::invalid_argument for unit strings, whose documented contract that is).
struct Outcome {
  bool accepted = false;
  std::string message;
};

// A broken promise of the code under test that is not a crash by itself (an accepted input
// whose resolved scene does not read back, an error that does not name the file, ...).
// Never caught by the entry points: the fuzzers abort on it and the corpus test fails.
class ContractViolation : public std::logic_error {
 public:
  using std::logic_error::logic_error;
};

// Lines "#--set key.path=value" of a scene text (YAML comments, so seeds stay valid scenes):
// the fuzzer's way of choosing `--set` overrides from its input.
std::vector<std::string> overrides_in(std::string_view scene_text);

// parse_scene(text) without overrides, then (if the text has any) with them. An accepted
// scene must write a resolved scene that parses again to an accepted scene.
struct SceneOutcome {
  Outcome plain;
  std::optional<Outcome> with_overrides;
  const Outcome& final() const { return with_overrides ? *with_overrides : plain; }
};
SceneOutcome feed_scene(std::string_view text, const std::string& path);

// parse_quantity, parse_quantity_as for every dimension the scene uses, length_unit_in_metres.
// An accepted quantity must be finite.
Outcome feed_quantity(std::string_view text);

// read_snapshot(path). An accepted snapshot must be consistent and rewrite to the same bytes.
Outcome feed_snapshot_file(const std::string& path);

// read_point_cloud(path). An accepted cloud must be consistent and survive a write/read.
Outcome feed_point_cloud_file(const std::string& path);

// For the fuzzers: writes `data` to a private temporary file (one per process, in
// $TMPDIR or /tmp) with the given extension and returns its path.
std::string write_temporary_input(std::string_view data, const std::string& extension);

}  // namespace mppm::fuzz
