// Peak resident memory of this process. VmHWM of /proc/self/status: unlike getrusage's
// ru_maxrss, which survives execve and so reports the launching (Python) process's size for
// small runs, it belongs to this program's own address space. ru_maxrss is the fallback off
// Linux.
#pragma once
#include <sys/resource.h>

#include <cstdint>
#include <fstream>
#include <string>

namespace mppm::accuracy {

inline std::int64_t peak_memory_bytes() {
  std::ifstream status("/proc/self/status");
  for (std::string line; std::getline(status, line);)
    if (line.rfind("VmHWM:", 0) == 0) return std::stoll(line.substr(6)) * 1024;  // "VmHWM:  1234 kB"
  rusage usage{};
  if (getrusage(RUSAGE_SELF, &usage) != 0) return 0;
  return static_cast<std::int64_t>(usage.ru_maxrss) * 1024;
}

}  // namespace mppm::accuracy
