// Calibration, no-fail zone, damage field and shape-tensor refresh of the damage effect.
#include "solver/bond_breakage.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <numeric>
#include <optional>
#include <stdexcept>
#include <string>

#include "common/lattice_offsets.hpp"
#include "solver/bond_kinematics.hpp"
#include "solver/damage_calibration.hpp"
#include "solver/exact_sum.hpp"
#include "solver/horizon_search.hpp"
#include "solver/parallel_policy.hpp"
#include "solver/point_stability.hpp"
#include "solver/shape_tensor.hpp"

namespace mppm::solver {

double continuum_critical_bond_work(int dimension, double g_cr, double horizon, double thickness) {
  // Sum of V_i V_j over the bonds that cross a unit area of a plane, in the continuum limit:
  // 3-D pi delta^4 / 4; 2-D (2/3) delta^3 t^2 per unit length, i.e. (2/3) delta^3 t per unit area
  // of the slice.
  if (dimension == 3) return 4.0 * g_cr / (std::numbers::pi * horizon * horizon * horizon * horizon);
  return 3.0 * g_cr / (2.0 * thickness * horizon * horizon * horizon);
}

double lattice_crossing_sum(int dimension, double horizon_factor) {
  // A plane between two lattice rows is crossed, per lattice cell of it, by b bonds of every
  // lattice offset (a, b[, c]) with b > 0 within the horizon (the same reach as the families:
  // |xi| <= delta + 1e-9 dx).
  double sum = 0.0;
  for_each_family_offset(dimension, horizon_factor, [&](int, int b, int) {
    if (b > 0) sum += b;
  });
  return sum;
}

double critical_bond_work(const DamageParameters& damage, int dimension, double spacing, double horizon_factor,
                          double thickness, double stabilization) {
  const double g_cr = damage.critical_energy_release_rate;
  if (damage.calibration == DamageCalibration::continuum)
    return continuum_critical_bond_work(dimension, g_cr, horizon_factor * spacing, thickness);
  if (damage.calibration == DamageCalibration::dissipation) {
    const auto rho = released_fraction(dimension, horizon_factor, stabilization);
    if (!rho)
      throw std::invalid_argument("the dissipation calibration is measured for " + released_fraction_ranges(dimension) +
                                  " in " + std::to_string(dimension) + "-D (this scene: horizon factor " +
                                  std::to_string(horizon_factor) + ", G_s " + std::to_string(stabilization) +
                                  "); use calibration: lattice, or a setting in that range");
    DamageParameters lattice = damage;
    lattice.calibration = DamageCalibration::lattice;
    return critical_bond_work(lattice, dimension, spacing, horizon_factor, thickness, stabilization) / *rho;
  }
  // Per cell of the plane (dx t in 2-D, dx^2 in 3-D) the crossing bonds carry S V^2 with V = dx^2 t
  // or dx^3: w_cr S dx^3 t = G_cr dx t (2-D), w_cr S dx^6 = G_cr dx^2 (3-D).
  const double s = lattice_crossing_sum(dimension, horizon_factor);
  const double dx3 = spacing * spacing * spacing;
  return dimension == 3 ? g_cr / (s * dx3 * spacing) : g_cr / (s * dx3 * thickness);
}

void mark_no_fail_zone(PointData& p, double depth, const std::vector<std::int32_t>& ignored, const PointCloud* whole) {
  std::fill(p.no_fail.begin(), p.no_fail.end(), 0);
  if (!(depth > 0.0)) return;
  const int D = p.dimension;
  auto on_boundary = [&](std::int32_t id) {
    return id > 0 && std::find(ignored.begin(), ignored.end(), id) == ignored.end();
  };
  std::vector<double> boundary;  // D coordinates per boundary point
  if (whole) {
    for (std::size_t k = 0; k < whole->boundary_id.size(); ++k)
      if (on_boundary(whole->boundary_id[k])) {
        const double xyz[3] = {whole->x[k], whole->y[k], D == 3 ? whole->z[k] : 0.0};
        boundary.insert(boundary.end(), xyz, xyz + D);
      }
  } else {
    for (std::size_t i = 0; i < p.owned; ++i)
      if (on_boundary(p.boundary_id[i])) boundary.insert(boundary.end(), &p.position[i * D], &p.position[(i + 1) * D]);
  }
  if (boundary.empty()) return;
  // The boundary points in a grid of cells of the depth (horizon_search.hpp): a point is in the
  // zone if one of them in the cells around its own is nearer than the depth. (A k-d tree's nearest
  // boundary point for every point took 0.5 s of the start-up of a 216 000-point 3-D block with
  // loaded faces; the same comparison of the same squared distances marks the same points.)
  const PointPositions at{D, boundary.data(), boundary.size() / static_cast<std::size_t>(D)};
  const CellGrid grid = make_grid(at, depth);
  const double depth2 = depth * depth;
  const auto n = static_cast<std::int64_t>(p.total());
#pragma omp parallel for schedule(static) if (thread_point_loop(p.total()))
  for (std::int64_t s = 0; s < n; ++s) {
    const auto i = static_cast<std::size_t>(s);
    p.no_fail[i] = any_point_nearer(at, grid, &p.position[i * D], depth2) ? 1 : 0;
  }
}

namespace {

double list_volume(const PointData& p, const BondFamilies& f, std::size_t i) {
  double v = 0.0;
  for (std::int64_t b = f.offset[i]; b < f.offset[i + 1]; ++b) v += p.volume[f.neighbor_of(b)];
  return v;
}

}  // namespace

std::vector<double> family_volumes(const PointData& p, const BondFamilies& f) {
  std::vector<double> v(p.owned);
  const auto n = static_cast<std::int64_t>(p.owned);
#pragma omp parallel for schedule(static) if (thread_bond_loop(f.bond_count()))
  for (std::int64_t i = 0; i < n; ++i) v[static_cast<std::size_t>(i)] = list_volume(p, f, static_cast<std::size_t>(i));
  return v;
}

void record_precut_family_volumes(PointData& p, const BondFamilies& f, const std::vector<double>& before) {
  p.precut_points.clear();
  p.precut_family_volume.clear();
  // A point whose list lost bonds sums to another value (a point where it would not, rounding
  // aside, needs no entry either: the sum over its list gives the same bits).
  for (std::size_t i = 0; i < p.owned; ++i) {
    if (list_volume(p, f, i) == before[i]) continue;
    p.precut_points.push_back(i);
    p.precut_family_volume.push_back(before[i]);
  }
}

namespace {

// The family volume recorded for a point whose list a pre-crack cut (none for the others).
std::optional<double> precut_family_volume(const PointData& p, std::size_t i) {
  const auto it = std::lower_bound(p.precut_points.begin(), p.precut_points.end(), i);
  if (it != p.precut_points.end() && *it == i)
    return p.precut_family_volume[static_cast<std::size_t>(it - p.precut_points.begin())];
  return std::nullopt;
}

}  // namespace

double family_volume_of(const PointData& p, const BondFamilies& f, std::size_t i) {
  if (const auto recorded = precut_family_volume(p, i)) return *recorded;
  return list_volume(p, f, i);
}

double point_damage(const PointData& p, const BondFamilies& f, std::size_t i) {
  // One walk over the list for the acting volume and the list's whole volume (the family volume
  // of a point that no pre-crack cut, the same sum list_volume makes): every snapshot with the
  // damage field visits every bond, and one walk instead of two halves that.
  double acting = 0.0, listed = 0.0;
  for (std::int64_t b = f.offset[i]; b < f.offset[i + 1]; ++b) {
    const double v = p.volume[f.neighbor_of(b)];
    listed += v;
    if (f.acting(b)) acting += v;
  }
  const double family = precut_family_volume(p, i).value_or(listed);
  if (!(family > 0.0)) return 0.0;
  return 1.0 - acting / family;
}

std::vector<double> damage_field(const PointData& p, const BondFamilies& f) {
  std::vector<double> d(p.owned, 0.0);
  for (std::size_t i = 0; i < p.owned; ++i) d[i] = point_damage(p, f, i);
  return d;
}

double family_breaking_energy(const PointData& p, const BondFamilies& f, const CosseratConstants& c, std::size_t i) {
  double family = 0.0;
  for (std::int64_t b = f.offset[i]; b < f.offset[i + 1]; ++b) family += p.volume[f.neighbor_of(b)];
  return 0.5 * c.critical_bond_work * p.volume[i] * family;
}

namespace {

// One update_after_breakage: the phases of the update over the state they share (the workspace's
// arrays, so that no phase allocates once they are warm). In a distributed run (docs/theory.md
// section 13) every process runs every phase in step with the others once any process has a
// breaking bond: a bond whose other end is a ghost is broken there by its owner (a note through
// the ghost exchange), the ghosts' shape terms and flags are fetched after each phase that changes
// them, and the decisions that the one-process update takes in index order are taken in global-id
// order (the stability detachments, one agreed point at a time). On one process none of this
// communicates.
class BreakageUpdater {
 public:
  BreakageUpdater(PointData& points, BondFamilies& bonds, const CosseratConstants& constants,
                  const InternalForceFunctions& functions, double limit, BreakageWorkspace& workspace)
      : p(points),
        f(bonds),
        c(constants),
        kernel(functions),
        block_eigenvalue_limit(limit),
        w(workspace),
        order(points),
        ghosts(points.ghost > 0 ? points.ghost_source : nullptr),
        group(points.processes) {}

  BreakageUpdate run();

 private:
  bool collect_breaking_bonds();
  void take_breaks_from_other_processes();
  void record(std::size_t i);
  void detach_on_energy_rise();
  void share_changed_points();
  void collect_stability_candidates();
  void detach_unstable_blocks();
  void break_bonds_of_detached();
  void refresh_and_measure_release();

  // Breaks entry b of point i (to j); a pair is counted once, at its end earlier in the order.
  void break_entry(std::size_t i, std::int64_t b, std::size_t j);
  // Adds to `out` the owned points with an acting bond to a ghost flagged in w.ghost_flag.
  void add_owned_neighbours_of_flagged_ghosts(std::vector<std::size_t>& out);
  // The ghosts' copies of the flags of `points` (owned, 1) in w.ghost_flag.
  void share_flags(const std::vector<std::size_t>& points);
  std::size_t ghost_index(std::int64_t global_id) const;
  bool any(bool here) const { return group ? group->any(here) : here; }

  PointData& p;
  BondFamilies& f;
  const CosseratConstants& c;
  const InternalForceFunctions& kernel;
  const double block_eigenvalue_limit;
  BreakageWorkspace& w;
  const PointOrder order;
  const GhostExchange* ghosts;  // null on one process
  const ProcessGroup* group;    // null on one process
  BreakageUpdate u;
};

BreakageUpdate BreakageUpdater::run() {
  p.refreshed_points.clear();
  if (!any(collect_breaking_bonds())) return u;
  u.broke = true;
  if (w.affected_index.size() != p.owned) w.affected_index.assign(p.owned, -1);
  take_breaks_from_other_processes();
  // The points whose families change in this update, in the order first met, with the energy they
  // stored just before (the breaking bonds still act, shape tensor as it was).
  w.affected.clear();
  w.energy_before.clear();
  for (const std::size_t i : w.changed) record(i);
  for (const auto& [i, b] : w.breaking) break_entry(i, b, f.neighbor_of(b));

  // Points to detach, found after the shape tensors of the changed points are recomputed
  // (docs/theory.md section 7, where the margins and what they were measured against are given;
  // tests/stability/README.md findings 3 and 8):
  //  - a singular shape tensor (docs/theory.md section 2);
  //  - a stored energy more than numerics.detach_energy_rise above the one before the point lost
  //    its bonds: a point left with a lopsided family can read a larger strain from the bonds it
  //    kept, which puts energy into the model;
  //  - any rise of the stored energy of an overloaded point, one that stored more than
  //    numerics.overload_factor times its family's breaking energy before the loss
  //    (family_breaking_energy): it is crushed, not separating, and would otherwise ratchet up by
  //    just under the relative margin at every loss;
  //  - a body point whose stiffness block the lopsided family pushed beyond what the run's time
  //    step allows (point_stability.hpp). The blocks of a changed point's neighbours depend on its
  //    shape tensor too, so that check covers them.
  // A detached point moves ballistically: its remaining bonds break (which changes its
  // neighbours in turn), except those to no-fail points; no-fail points are never detached by the
  // last two rules. Decided serially and in index order (global-id order across processes): the
  // same for any thread count and partition. Points
  // detached from the start (isolated by the geometry) are left as they are. Rounds of this run
  // until no family changes.
  while (any(!w.changed.empty())) {
    detach_on_energy_rise();
    share_changed_points();
    if (block_eigenvalue_limit > 0.0) detach_unstable_blocks();
    break_bonds_of_detached();
  }
  refresh_and_measure_release();
  return u;
}

void BreakageUpdater::break_entry(std::size_t i, std::int64_t b, std::size_t j) {
  f.break_bond(b);
  if (order(i) < order(j)) ++u.broken_pairs;
}

std::size_t BreakageUpdater::ghost_index(std::int64_t global_id) const {
  const auto first = p.global_id.begin() + static_cast<std::ptrdiff_t>(p.owned);
  const auto it = std::lower_bound(first, p.global_id.end(), global_id);
  if (it == p.global_id.end() || *it != global_id)
    throw std::logic_error("update_after_breakage: point " + std::to_string(global_id) + " is not a ghost here");
  return static_cast<std::size_t>(it - p.global_id.begin());
}

template <int D, int R, bool Polar>
bool stretched(const PointData& p, const BondFamilies& f, std::size_t i, std::int64_t b, std::size_t j) {
  double xi[D], U[D];
  bond_vector<D>(f, p.position.data(), i, b, xi);
  const double* wi = Polar ? p.rotation.data() + i * R : nullptr;
  const double* wj = Polar ? p.rotation.data() + j * R : nullptr;
  kernel::composite_state<D, R, Polar>(p.displacement.data() + i * D, p.displacement.data() + j * D, wi, wj, xi, U);
  double change = 0.0;  // |xi + U|^2 - |xi|^2
  for (int a = 0; a < D; ++a) change += (2.0 * xi[a] + U[a]) * U[a];
  return change > 0.0;
}

// Whether bond b of point i (to j) is stretched, |xi + U| > |xi|, with the composite state U of
// docs/theory.md section 2 (the micro-rotations included with micropolar), in the state of the
// force evaluation that counted it.
bool bond_stretched(const PointData& p, const BondFamilies& f, std::size_t i, std::int64_t b, std::size_t j) {
  const bool polar = p.rotation_components > 0;
  if (p.dimension == 2) return polar ? stretched<2, 1, true>(p, f, i, b, j) : stretched<2, 1, false>(p, f, i, b, j);
  return polar ? stretched<3, 3, true>(p, f, i, b, j) : stretched<3, 3, false>(p, f, i, b, j);
}

// The candidates: the kernel counts a bond at the lower end, which holds the pair's work, when its
// work reaches the critical work (the kernel books no work on a bond with a no-fail end, so those
// stay at zero). They break, except compressed ones with material.damage.compressed_bonds: hold
// (decided here only, once per candidate); their two ends are the points whose families change
// (w.changed, owned, sorted); an end that is a ghost is noted for its owner. They still act until
// they are broken. False when no bond of this process breaks.
bool BreakageUpdater::collect_breaking_bonds() {
  std::vector<std::size_t>& changed = w.changed;
  changed.clear();
  w.breaking.clear();  // the entries of this process's points, with their points
  w.notes.clear();
  std::size_t counted = 0, held = 0, pairs = 0;
  for (std::size_t i = 0; i < p.owned; ++i) {
    if (p.bonds_broken[i] == 0) continue;
    counted += static_cast<std::size_t>(p.bonds_broken[i]);
    const std::size_t pairs_before = pairs;
    const std::int64_t split = f.first_pair_bond(i);
    for (std::int64_t b = split; b < f.offset[i + 1]; ++b) {
      if (!f.acting(b)) continue;
      const std::size_t j = f.neighbor_of(b);
      const double work = f.work[static_cast<std::size_t>(f.pair_offset[i] + (b - split))];
      if (!(work >= c.critical_bond_work)) continue;
      if (c.hold_compressed_bonds && !bond_stretched(p, f, i, b, j)) {
        ++held;
        continue;
      }
      ++pairs;
      w.breaking.push_back({i, b});
      if (j < p.owned) {
        w.breaking.push_back({j, mirror_bond(f, i, j, order)});
        changed.push_back(j);
      } else {
        w.notes.push_back({j, order(i)});
      }
    }
    if (pairs > pairs_before) changed.push_back(i);
  }
  if (pairs + held != counted)
    throw std::logic_error("update_after_breakage: the bonds at their critical work are not those the kernel counted");
  return !changed.empty();
}

// A distributed run: the bonds other processes broke at their (lower) end whose other end is a
// point of this one break here too; their points change.
void BreakageUpdater::take_breaks_from_other_processes() {
  if (ghosts) {
    for (const PointNote& note : ghosts->notify_owners(w.notes)) {
      const std::size_t i = ghost_index(note.value);
      const std::int64_t mirror = mirror_bond(f, i, note.point, order);
      if (mirror < 0) throw std::logic_error("update_after_breakage: a bond broken elsewhere has no end here");
      w.breaking.push_back({note.point, mirror});
      w.changed.push_back(note.point);
    }
  }
  std::sort(w.changed.begin(), w.changed.end());
  w.changed.erase(std::unique(w.changed.begin(), w.changed.end()), w.changed.end());
}

// Point i among the affected points (once), with the energy it stores now.
void BreakageUpdater::record(std::size_t i) {
  if (i >= p.owned || w.affected_index[i] >= 0) return;
  w.affected_index[i] = static_cast<std::int64_t>(w.affected.size());
  w.affected.push_back(i);
  w.energy_before.push_back(kernel.point_energy(p, f, c, i).total());
}

// The shape tensors of the changed points recomputed; the points they left singular, and those
// whose stored energy rose too much (numerics.detach_energy_rise, numerics.overload_factor),
// detached (w.detach).
void BreakageUpdater::detach_on_energy_rise() {
  const std::vector<std::size_t>& changed = w.changed;
  w.was_detached.resize(changed.size());
  for (std::size_t k = 0; k < changed.size(); ++k) w.was_detached[k] = p.detached[changed[k]];
  update_shape_tensors(p, f, c, changed);
  w.detach.clear();
  for (std::size_t k = 0; k < changed.size(); ++k) {
    const std::size_t i = changed[k];
    if (w.was_detached[k]) continue;
    if (p.detached[i]) {
      w.detach.push_back(i);
      continue;
    }
    if (p.no_fail[i]) continue;
    const double before = w.energy_before[static_cast<std::size_t>(w.affected_index[i])];
    const double after = kernel.point_energy(p, f, c, i).total();
    if (!(after > before)) continue;
    // With compressed_bonds: hold nothing is crushed (docs/theory.md section 7), so the overload
    // rule, which takes a point holding more than its family can dissipate for crushed, is off.
    const bool overloaded = !c.hold_compressed_bonds && before > c.overload_factor * family_breaking_energy(p, f, c, i);
    if (overloaded || after > (1.0 + c.detach_energy_rise) * before) {
      detach_point(p, i);
      w.detach.push_back(i);
      ++u.energy_detached;
    }
  }
}

// A distributed run: the ghosts' shape terms and detached flags after the changed points' new
// ones, and which ghosts changed (their neighbours here are stability candidates).
void BreakageUpdater::share_changed_points() {
  if (!ghosts) return;
  share_shape_terms(p, true);
  share_flags(w.changed);
}

void BreakageUpdater::share_flags(const std::vector<std::size_t>& points) {
  w.flag_values.assign(p.total(), 0.0);
  for (const std::size_t i : points) w.flag_values[i] = 1.0;
  ghosts->update_ghosts(w.flag_values, 1);
  w.ghost_flag.assign(p.total(), 0);
  for (std::size_t g = p.owned; g < p.total(); ++g) w.ghost_flag[g] = w.flag_values[g] != 0.0 ? 1 : 0;
}

void BreakageUpdater::add_owned_neighbours_of_flagged_ghosts(std::vector<std::size_t>& out) {
  if (!ghosts) return;
  if (w.ghost_neighbour_offset.size() != p.ghost + 1) w.index_ghost_neighbours(p, f);
  for (std::size_t g = p.owned; g < p.total(); ++g) {
    if (!w.ghost_flag[g]) continue;
    const std::size_t k = g - p.owned;
    for (std::size_t e = w.ghost_neighbour_offset[k]; e < w.ghost_neighbour_offset[k + 1]; ++e)
      if (f.acting(w.ghost_neighbour_bond[e])) out.push_back(w.ghost_neighbour[e]);
  }
}

// The changed points and their owned neighbours (a ghost is its owner's candidate), sorted.
void BreakageUpdater::collect_stability_candidates() {
  std::vector<std::size_t>& candidates = w.candidates;
  candidates.clear();
  for (const std::size_t i : w.changed) {
    candidates.push_back(i);
    for (std::int64_t b = f.offset[i]; b < f.offset[i + 1]; ++b)
      if (f.acting(b) && f.neighbor_of(b) < p.owned) candidates.push_back(f.neighbor_of(b));
  }
  add_owned_neighbours_of_flagged_ghosts(candidates);
  std::sort(candidates.begin(), candidates.end());
  candidates.erase(std::unique(candidates.begin(), candidates.end()), candidates.end());
}

// The stability blocks: the changed points and their neighbours whose stiffness block exceeds
// block_eigenvalue_limit detached (w.detach).
void BreakageUpdater::detach_unstable_blocks() {
  collect_stability_candidates();
  const std::vector<std::size_t>& candidates = w.candidates;
  // The blocks (an eigenvalue problem each, for every changed point's neighbours: the bulk of
  // this update's work) are evaluated in parallel first; the decisions below stay serial and
  // in global order. A detachment changes its neighbours' blocks, so once one happened in this
  // round the later candidates are evaluated again, as a serial loop would see them. Across
  // processes each detachment is agreed: the first candidate in global order above the limit on
  // any process (the lowest global id) is detached by its owner, the ghosts learn it, and the
  // search goes on after it everywhere.
  auto checked = [&](std::size_t i) { return !p.detached[i] && p.region[i] == 0 && !p.no_fail[i]; };
  std::vector<double>& eigenvalue = w.candidate_eigenvalue;
  eigenvalue.assign(candidates.size(), 0.0);
  const auto count = static_cast<std::int64_t>(candidates.size());
#pragma omp parallel for schedule(dynamic, 16) if (thread_block_loop(candidates.size()))
  for (std::int64_t k = 0; k < count; ++k) {
    const std::size_t i = candidates[static_cast<std::size_t>(k)];
    if (checked(i)) eigenvalue[static_cast<std::size_t>(k)] = point_block_eigenvalue(p, f, c, i);
  }
  constexpr std::int64_t kNone = std::numeric_limits<std::int64_t>::max();
  bool detached_this_round = false;
  std::size_t next = 0;
  for (;;) {
    std::size_t found = candidates.size();
    for (std::size_t k = next; k < candidates.size() && found == candidates.size(); ++k) {
      const std::size_t i = candidates[k];
      if (!checked(i)) continue;
      const double block = detached_this_round ? point_block_eigenvalue(p, f, c, i) : eigenvalue[k];
      if (block > block_eigenvalue_limit) found = k;
    }
    const std::int64_t mine = found < candidates.size() ? order(candidates[found]) : kNone;
    const std::int64_t first = group ? group->lowest(mine) : mine;
    if (first == kNone) return;
    if (mine == first) {
      const std::size_t i = candidates[found];
      record(i);
      detach_point(p, i);
      w.detach.push_back(i);
      ++u.unstable_detached;
    }
    detached_this_round = true;
    share_shape_terms(p, true);
    next = static_cast<std::size_t>(std::upper_bound(candidates.begin(), candidates.end(), first,
                                                     [&](std::int64_t v, std::size_t i) { return v < order(i); }) -
                                    candidates.begin());
  }
}

// The detachment round: the remaining bonds of the points detached in this round break (at both
// ends: an end on another process through a note to its owner); their other ends are the next
// round's changed points.
void BreakageUpdater::break_bonds_of_detached() {
  std::vector<std::size_t>& next = w.next;
  std::sort(w.detach.begin(), w.detach.end());
  next.clear();
  w.notes.clear();
  for (const std::size_t i : w.detach) {
    ++u.newly_detached;
    for (std::int64_t b = f.offset[i]; b < f.offset[i + 1]; ++b) {
      if (!f.acting(b)) continue;
      const std::size_t j = f.neighbor_of(b);
      // A bond with a no-fail end never breaks (docs/theory.md section 7), not even here: the detached
      // point stays tied to the protected boundary by it (its own stress is zero; the pair
      // force is then the no-fail point's alone).
      if (p.no_fail[j]) continue;
      if (j >= p.owned) {
        break_entry(i, b, j);
        w.notes.push_back({j, order(i)});
        continue;
      }
      record(j);
      const std::int64_t rb = mirror_bond(f, i, j, order);
      break_entry(i, b, j);
      if (rb >= 0) break_entry(j, rb, i);
      next.push_back(j);
    }
  }
  if (ghosts) {
    // The other ends on this process of the bonds other processes broke (an end already broken
    // here, both ends detached in this round, is left as it is).
    for (const PointNote& note : ghosts->notify_owners(w.notes)) {
      const std::size_t i = ghost_index(note.value), j = note.point;
      const std::int64_t rb = mirror_bond(f, i, j, order);
      if (rb < 0 || !f.acting(rb)) continue;
      record(j);
      break_entry(j, rb, i);
      next.push_back(j);
    }
  }
  std::sort(next.begin(), next.end());
  next.erase(std::unique(next.begin(), next.end()), next.end());
  w.changed.swap(next);
}

// The refresh: the step's forces again without the broken bonds (kernel::refresh_after_breakage)
// at the affected points and their neighbours, which also refreshes the per-point energies of the
// affected points. The stored energy the breaks release is what these points stored before minus
// what they store now, at the same displacements and rotations (only their energies changed: a
// point's energy depends on its own family only). Summed exactly (exact_sum.hpp): the same bits
// for any thread count or partition. (The integrator adds the kick's share, from the forces
// before the refresh.)
void BreakageUpdater::refresh_and_measure_release() {
  w.sorted.assign(w.affected.begin(), w.affected.end());
  std::sort(w.sorted.begin(), w.sorted.end());
  std::vector<std::size_t>& around = p.refreshed_points;
  around = w.sorted;
  for (const std::size_t i : w.sorted)
    for (std::int64_t b = f.offset[i]; b < f.offset[i + 1]; ++b)
      if (f.acting(b) && f.neighbor_of(b) < p.owned) around.push_back(f.neighbor_of(b));
  if (ghosts) {
    share_flags(w.sorted);
    add_owned_neighbours_of_flagged_ghosts(around);
  }
  std::sort(around.begin(), around.end());
  around.erase(std::unique(around.begin(), around.end()), around.end());
  kernel.refresh_after_breakage(p, f, c);
  ExactSum released;
  for (std::size_t k = 0; k < w.affected.size(); ++k) {
    const std::size_t i = w.affected[k];
    const StoredEnergy elastic = kernel.elastic_energy(p, c, i);
    double after = elastic.force_stress + p.stabilization_energy[i];
    if (!p.rotation.empty()) after += elastic.couple_stress;
    if (!p.fluid_content_change.empty()) after += elastic.fluid;
    released += w.energy_before[k] - after;
    w.affected_index[i] = -1;
  }
  u.released_energy = group ? group->sum(released) : released.value();
}

}  // namespace

void BreakageWorkspace::index_ghost_neighbours(const PointData& p, const BondFamilies& f) {
  ghost_neighbour_offset.assign(p.ghost + 1, 0);
  for (std::size_t i = 0; i < p.owned; ++i)
    for (std::int64_t b = f.offset[i]; b < f.offset[i + 1]; ++b)
      if (f.neighbor_of(b) >= p.owned) ++ghost_neighbour_offset[f.neighbor_of(b) - p.owned + 1];
  std::partial_sum(ghost_neighbour_offset.begin(), ghost_neighbour_offset.end(), ghost_neighbour_offset.begin());
  ghost_neighbour.resize(ghost_neighbour_offset.back());
  ghost_neighbour_bond.resize(ghost_neighbour_offset.back());
  std::vector<std::size_t> fill(ghost_neighbour_offset.begin(), ghost_neighbour_offset.end() - 1);
  for (std::size_t i = 0; i < p.owned; ++i)
    for (std::int64_t b = f.offset[i]; b < f.offset[i + 1]; ++b)
      if (f.neighbor_of(b) >= p.owned) {
        const std::size_t e = fill[f.neighbor_of(b) - p.owned]++;
        ghost_neighbour[e] = i;
        ghost_neighbour_bond[e] = b;
      }
}

BreakageUpdate update_after_breakage(PointData& p, BondFamilies& f, const CosseratConstants& c,
                                     const InternalForceFunctions& kernel, double block_eigenvalue_limit,
                                     BreakageWorkspace& w) {
  return BreakageUpdater(p, f, c, kernel, block_eigenvalue_limit, w).run();
}

}  // namespace mppm::solver
