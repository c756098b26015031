// Progress display for long stages: an updating line on a terminal, a plain line every few
// seconds otherwise (logs, CI). Silent with --quiet.
#pragma once
#include <chrono>
#include <cstdint>
#include <string>

namespace mppm {

class Progress {
 public:
  Progress(std::string label, std::int64_t total, bool quiet);
  // `done` units finished out of `total`; `detail` is appended (e.g. "t = 1.2e-5 s").
  void update(std::int64_t done, const std::string& detail = {});
  void finish(const std::string& detail = {});

 private:
  std::string label_;
  std::int64_t total_;
  bool quiet_;
  bool terminal_;
  std::chrono::steady_clock::time_point start_, last_;
};

// Human-readable byte count ("1.3 GiB").
std::string format_bytes(double bytes);

}  // namespace mppm
