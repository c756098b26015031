// Family search (neighbour_search.hpp: on a lattice by its sites, else by cells); two passes (count,
// fill) over points in parallel, each point writing only its own bond range.
#include "solver/bond_families.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <iterator>
#include <numeric>
#include <stdexcept>

#include "solver/neighbour_search.hpp"
#include "solver/parallel_policy.hpp"

namespace mppm::solver {

namespace {

// Sorts one family's entries [first, last) by their neighbours' PointOrder: the index, or the
// global id in a distributed run, whose process then sums each point's bonds in the order of the
// single process (its local indices put the ghosts after the owned points). A lattice's search finds
// them by offset, already in that order only where the points are numbered row by row.
template <class Iterator, class NeighbourOf>
void sort_by_neighbour_order(Iterator first, Iterator last, const PointOrder& order, NeighbourOf neighbour_of) {
  using Value = typename std::iterator_traits<Iterator>::value_type;
  const auto before = [&](const Value& a, const Value& b) {
    return order(static_cast<std::size_t>(neighbour_of(a))) < order(static_cast<std::size_t>(neighbour_of(b)));
  };
  if (!std::is_sorted(first, last, before)) std::sort(first, last, before);
}

}  // namespace

BondFamilies build_families(const PointData& p, const FamilyOptions& o) {
  if (!(o.horizon > 0.0)) throw std::invalid_argument("build_families: horizon must be positive");
  const int D = p.dimension;
  const bool periodic = o.period[0] > 0.0 || o.period[1] > 0.0 || o.period[2] > 0.0;
  for (int a = 0; a < D; ++a)
    if (o.period[a] > 0.0 && o.period[a] <= 2.0 * o.horizon)
      throw std::invalid_argument("build_families: a period must exceed twice the horizon");
  const double reach = bond_reach(o.horizon, o.spacing);
  const NeighbourSearch search({D, p.position.data(), p.total()}, reach, o.spacing, o.period);

  BondFamilies f;
  f.dimension = D;
  const std::size_t n = p.owned;
  f.offset.assign(n + 1, 0);
  const auto sn = static_cast<std::int64_t>(n);
#pragma omp parallel for schedule(static) if (thread_point_loop(n * 8))
  for (std::int64_t s = 0; s < sn; ++s) {
    std::int64_t count = 0;
    search.for_each(static_cast<std::size_t>(s), [&](std::size_t, const double*) { ++count; });
    f.offset[s + 1] = count;
  }
  std::partial_sum(f.offset.begin(), f.offset.end(), f.offset.begin());
  const auto bonds = static_cast<std::size_t>(f.offset[n]);
  if (bonds > static_cast<std::size_t>(INT32_MAX) * 64) throw std::length_error("build_families: too many bonds");
  f.neighbor.resize(bonds);
  if (periodic) f.xi.resize(bonds * D);
  const PointOrder order(p);
#pragma omp parallel if (thread_bond_loop(bonds))
  {
    // With periods, one list per thread of the neighbours and their bond vectors (a period shifts
    // the search's), reused from point to point; without, the indices go straight into the family.
    std::vector<std::pair<std::int32_t, std::array<double, 3>>> found;
#pragma omp for schedule(static)
    for (std::int64_t s = 0; s < sn; ++s) {
      const auto i = static_cast<std::size_t>(s);
      const auto first = f.neighbor.begin() + f.offset[i];
      if (!periodic) {
        auto next = first;
        search.for_each(i, [&](std::size_t j, const double*) { *next++ = static_cast<std::int32_t>(j); });
        sort_by_neighbour_order(first, next, order, [](std::int32_t j) { return j; });
        continue;
      }
      found.clear();
      search.for_each(i, [&](std::size_t j, const double* xi) {
        found.push_back({static_cast<std::int32_t>(j), {xi[0], xi[1], D == 3 ? xi[2] : 0.0}});
      });
      sort_by_neighbour_order(found.begin(), found.end(), order, [](const auto& e) { return e.first; });
      std::int64_t b = f.offset[i];
      for (const auto& [j, xi] : found) {
        f.neighbor[b] = j;
        for (int a = 0; a < D; ++a) f.xi[b * D + a] = xi[a];
        ++b;
      }
    }
  }
  if (p.ghost > 0) split_interior_and_border(f, p.owned);
  return f;
}

void split_interior_and_border(BondFamilies& f, std::size_t owned) {
  f.interior_points.clear();
  f.border_points.clear();
  for (std::size_t i = 0; i < owned; ++i) {
    const auto* first = f.neighbor.data() + f.offset[i];
    const auto* last = f.neighbor.data() + f.offset[i + 1];
    const bool border = std::any_of(first, last, [&](std::int32_t e) { return BondFamilies::index_of(e) >= owned; });
    (border ? f.border_points : f.interior_points).push_back(i);
  }
}

namespace {

// A hash of the pair {i, j} (i < j), spread over 64 bits (the finalizer of splitmix64).
std::uint64_t pair_hash(std::uint64_t i, std::uint64_t j) {
  std::uint64_t x = i * 0x9E3779B97F4A7C15ull + j * 0xC2B2AE3D27D4EB4Full;
  x ^= x >> 30;
  x *= 0xBF58476D1CE4E5B9ull;
  x ^= x >> 27;
  x *= 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}

}  // namespace

void index_bond_pairs(BondFamilies& f, PointOrder order) {
  const auto n = static_cast<std::int64_t>(f.offset.size()) - 1;
  f.pair_offset.assign(static_cast<std::size_t>(n) + 1, 0);
  // Every bond between owned points stored at both ends: then the sum (mod 2^64) of its pair's
  // hash, added from the lower end and subtracted from the upper, vanishes; a bond stored at one
  // end only, or twice at one, leaves its hash in it (and bonds in error cancel only if their
  // hashes do, at odds of 2^-64). (A bisection of the neighbour's list for every bond cost 4 ms of
  // the crack-branching plate's start-up, 737 752 bonds at 1 thread.)
  std::uint64_t unmatched = 0;
  bool ghost_without_processes = false;
#pragma omp parallel for schedule(static) reduction(+ : unmatched) reduction(|| : ghost_without_processes) \
    if (thread_bond_loop(f.bond_count()))
  for (std::int64_t i = 0; i < n; ++i) {
    const auto low = static_cast<std::uint64_t>(i);
    for (std::int64_t b = f.offset[i]; b < f.offset[i + 1]; ++b) {
      const auto j = static_cast<std::uint64_t>(f.neighbor_of(b));
      if (j >= static_cast<std::uint64_t>(n)) {
        if (order.global_id.empty()) ghost_without_processes = true;  // one process has no ghosts
        continue;
      }
      unmatched += j > low ? pair_hash(low, j) : -pair_hash(j, low);
    }
    f.pair_offset[i + 1] = f.offset[i + 1] - first_bond_above(f, static_cast<std::size_t>(i), order);
  }
  if (unmatched != 0 || ghost_without_processes)
    throw std::logic_error("index_bond_pairs: a bond is not stored at both of its (owned) ends");
  std::partial_sum(f.pair_offset.begin(), f.pair_offset.end(), f.pair_offset.begin());
  f.work.assign(static_cast<std::size_t>(f.pair_offset[n]), 0.0);
}

double bond_work(const BondFamilies& f, std::size_t i, std::int64_t b) {
  std::size_t low = i;
  std::int64_t entry = b;
  const std::size_t j = f.neighbor_of(b);
  if (j < i) {
    low = j;
    entry = mirror_bond(f, i, j);
  }
  return f.work[static_cast<std::size_t>(f.pair_offset[low] + (entry - first_bond_above(f, low)))];
}

}  // namespace mppm::solver
