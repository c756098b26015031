// The partition summary's one-line description (partition_summary.hpp).
#include "solver/partition_summary.hpp"

#include <sstream>

namespace mppm::solver {

std::string describe(const PartitionSummary& summary) {
  auto list = [](const std::vector<std::int64_t>& v) {
    std::string out;
    for (std::size_t k = 0; k < v.size(); ++k) out += (k ? " / " : "") + std::to_string(v[k]);
    return out;
  };
  std::ostringstream s;
  s.precision(4);
  s << summary.points.size() << (summary.points.size() == 1 ? " process" : " processes") << ": points "
    << list(summary.points) << ", ghosts " << list(summary.ghosts) << ", bonds " << list(summary.bonds)
    << ", imbalance " << summary.imbalance;
  return s.str();
}

}  // namespace mppm::solver
