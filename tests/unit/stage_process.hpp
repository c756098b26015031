// Runs an mppm executable as a child process, the way a user does, for the reliability tests:
// exit code, stderr, peak resident memory, and optionally a file-size limit (RLIMIT_FSIZE with
// SIGXFSZ ignored, so that writes past it fail with EFBIG like writes to a full disk).
#pragma once
#include <fcntl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <optional>
#include <string>
#include <vector>

namespace mppm::testing {

inline std::string binary(const std::string& name) { return std::string(MPPM_BINARY_DIR) + "/bin/" + name; }

struct StageOutcome {
  int code = -1;                    // exit code; 128 + signal when killed
  std::string err;                  // stderr
  std::int64_t peak_rss_bytes = 0;  // ru_maxrss of the child
};

inline StageOutcome run_stage_process(const std::vector<std::string>& args,
                                      std::optional<rlim_t> file_size_limit = std::nullopt) {
  const std::string err_path =
      std::string(MPPM_BINARY_DIR) + "/test_scratch/stage_stderr_" + std::to_string(::getpid());
  const pid_t pid = ::fork();
  if (pid == 0) {
    if (file_size_limit) {
      std::signal(SIGXFSZ, SIG_IGN);  // inherited through exec: writes fail with EFBIG
      rlimit limit{};
      getrlimit(RLIMIT_FSIZE, &limit);
      limit.rlim_cur = *file_size_limit;
      setrlimit(RLIMIT_FSIZE, &limit);
    }
    // stderr goes to a regular file and so is under the limit too: the tests' limits are far
    // above the length of an error message.
    const int err = ::open(err_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    const int null = ::open("/dev/null", O_WRONLY);
    if (err < 0 || null < 0) ::_exit(127);
    ::dup2(null, STDOUT_FILENO);
    ::dup2(err, STDERR_FILENO);
    std::vector<char*> argv;
    for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    ::execv(argv[0], argv.data());
    ::_exit(127);
  }
  StageOutcome outcome;
  int status = 0;
  rusage usage{};
  if (pid < 0 || ::wait4(pid, &status, 0, &usage) != pid) return outcome;
  outcome.code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  outcome.peak_rss_bytes = static_cast<std::int64_t>(usage.ru_maxrss) * 1024;  // ru_maxrss is in KiB on Linux
  std::ifstream in(err_path, std::ios::binary);
  outcome.err.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  in.close();
  std::remove(err_path.c_str());
  return outcome;
}

}  // namespace mppm::testing
