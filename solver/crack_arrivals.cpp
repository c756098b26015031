// The crack-arrival table (crack_arrivals.hpp).
#include "solver/crack_arrivals.hpp"

#include "common/crack_path.hpp"
#include "common/input_error.hpp"
#include "solver/bond_breakage.hpp"

namespace mppm::solver {

void CrackArrivals::arrive(std::size_t i, double time) {
  arrived_[i] = 1;
  points_.push_back(i);
  times_.push_back(time);
}

void CrackArrivals::start(const PointData& p, const BondFamilies& f, double time) {
  arrived_.assign(p.owned, 0);
  points_.clear();
  times_.clear();
  for (std::size_t i = 0; i < p.owned; ++i)
    if (point_damage(p, f, i) >= kCrackDamageThreshold) arrive(i, time);
}

void CrackArrivals::update(const PointData& p, const BondFamilies& f, const std::vector<std::size_t>& changed,
                           double time) {
  for (const std::size_t i : changed)
    if (i < arrived_.size() && !arrived_[i] && point_damage(p, f, i) >= kCrackDamageThreshold) arrive(i, time);
}

void CrackArrivals::restore(std::vector<std::uint64_t> points, std::vector<double> times, std::size_t point_count,
                            const std::string& file) {
  auto refuse = [&](const std::string& what) {
    throw InputError(file + ": corrupted checkpoint (the crack-arrival table " + what + ")");
  };
  if (points.size() != times.size())
    refuse("has " + std::to_string(points.size()) + " points but " + std::to_string(times.size()) + " times");
  std::vector<std::uint8_t> arrived(point_count, 0);
  for (std::size_t k = 0; k < points.size(); ++k) {
    if (points[k] >= point_count)
      refuse("names point " + std::to_string(points[k]) + " of " + std::to_string(point_count));
    if (arrived[points[k]]) refuse("lists point " + std::to_string(points[k]) + " twice");
    if (k > 0 && !(times[k] >= times[k - 1])) refuse("is not in time order");
    arrived[points[k]] = 1;
  }
  arrived_ = std::move(arrived);
  points_ = std::move(points);
  times_ = std::move(times);
}

}  // namespace mppm::solver
