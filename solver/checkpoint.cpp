// Checkpoint contents (the list in checkpoint.hpp) and their restoration.
#include "solver/checkpoint.hpp"

#include <algorithm>
#include <filesystem>
#include <functional>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "common/checksummed_binary.hpp"
#include "common/input_error.hpp"
#include "solver/distributed_bond_state.hpp"
#include "solver/distributed_snapshot.hpp"
#include "solver/shape_tensor.hpp"

namespace mppm::solver {

namespace {

// Every per-point and per-bond array a run carries from one step to the next, by name, for the
// model's effects (ModelRef is Model or const Model: one list for writing and for restoring).
template <class ModelRef, class Visit>
void visit_carried_arrays(ModelRef& model, Visit&& visit) {
  auto& p = model.points;
  visit("displacement", p.displacement);
  visit("velocity", p.velocity);
  visit("force", p.force);
  if (model.effects.micropolar) {
    visit("rotation", p.rotation);
    visit("rotation_rate", p.spin);
    visit("moment", p.moment);
  }
  if (model.effects.viscoplasticity) {
    // The return map starts the step from the previous evaluation's strain and wryness.
    visit("strain", p.strain);
    visit("plastic_strain", p.plastic_strain);
    visit("equivalent_plastic_strain", p.equivalent_plastic_strain);
    visit("plastic_dissipation", p.plastic_dissipation);
    if (model.effects.micropolar) {
      visit("wryness", p.wryness);
      visit("plastic_wryness", p.plastic_wryness);
    }
  }
  if (model.effects.pore_fluid) {
    // The flow state; the flow updates read the pressure and the last evaluation's strain.
    visit("fluid_content_change", p.fluid_content_change);
    visit("pore_pressure", p.pore_pressure);
    if (!model.effects.viscoplasticity) visit("strain", p.strain);
    // Unsaturated: the stored fluid energy is booked per point (solver/unsaturated_coupling.hpp).
    if (!p.fluid_energy.empty()) visit("stored_fluid_energy", p.fluid_energy);
  }
  if (model.effects.damage) {
    auto& f = model.bonds;
    // The neighbour lists with the broken bonds marked (BondFamilies::kBrokenBit); restored by
    // restore_broken_bonds, which checks them against the lists built from the points.
    visit("bond_neighbor", f.neighbor);
    visit("bond_work", f.work);
    visit("shape_inverse", p.shape_inverse);
    visit("stabilization_ck", p.stabilization_ck);
    visit("detached", p.detached);
    visit("no_fail", p.no_fail);
    visit("bonds_broken", p.bonds_broken);
    // The bond-work increment of the next step starts from the last evaluation: its displacement
    // and rotation, and its force / moment tensors, which the next evaluation swaps into the
    // previous_* arrays (the previous_* tensors held now are overwritten before being read).
    // The tensors as stored, by columns (point_data.hpp); named so, a checkpoint of the former
    // layout (by rows, named force_tensor and moment_tensor) is refused rather than misread.
    visit("previous_displacement", p.previous_displacement);
    visit("force_tensor_by_columns", p.force_tensor);
    if (model.effects.micropolar) {
      visit("stabilization_rot", p.stabilization_rot);
      visit("previous_rotation", p.previous_rotation);
      visit("moment_tensor_by_columns", p.moment_tensor);
    }
  }
}

std::vector<double> energy_values(const EnergyState& e) {
  return {e.kinetic,
          e.rotational_kinetic,
          e.elastic,
          e.stabilization,
          e.external_work,
          e.plastic_dissipation,
          e.fracture_dissipation,
          e.kinetic_terms};
}

// The fluid's items of the energy state (pore fluid runs only: the file of a dry run is unchanged).
std::vector<double> fluid_energy_values(const EnergyState& e) {
  return {e.fluid_stored, e.flow_dissipation, e.initial_fluid_volume, e.fluid_volume, e.flow_splitting};
}
void restore_fluid_energy(const std::vector<double>& v, EnergyState& e) {
  e.fluid_stored = v[0];
  e.flow_dissipation = v[1];
  e.initial_fluid_volume = v[2];
  e.fluid_volume = v[3];
  e.flow_splitting = v[4];
}

EnergyState energy_from(const std::vector<double>& v) {
  EnergyState e;
  e.kinetic = v[0];
  e.rotational_kinetic = v[1];
  e.elastic = v[2];
  e.stabilization = v[3];
  e.external_work = v[4];
  e.plastic_dissipation = v[5];
  e.fracture_dissipation = v[6];
  e.kinetic_terms = v[7];
  return e;
}

// A fixed-length array of scalars, refused when it has another length.
template <class T>
std::vector<T> scalars(const CheckpointFile& file, const std::string& name, std::size_t count) {
  std::vector<T> v(count);
  file.restore(name, v);
  return v;
}

// Breaks the bonds the checkpoint's neighbour lists mark broken in the model's lists (built from the
// same points, so the same entries apart from the marks).
void restore_broken_bonds(const CheckpointFile& file, BondFamilies& f) {
  auto saved = file.array<std::int32_t>("bond_neighbor");
  bool same = saved.size() == f.neighbor.size();
  for (std::size_t b = 0; same && b < saved.size(); ++b) same = BondFamilies::index_of(saved[b]) == f.neighbor_of(b);
  if (!same)
    throw InputError(file.path + ": the checkpoint's bonds are not those of these points (corrupted checkpoint?)");
  f.neighbor.swap(saved);
}

constexpr const char* kArrivalPoints = "crack_arrival_points";
constexpr const char* kFluidBoundaries = "fluid_boundary_flows";
constexpr const char* kArrivalTimes = "crack_arrival_times";

void restore_crack_arrivals(const CheckpointFile& file, Model& model, std::uint64_t point_count) {
  if (!file.has(kArrivalPoints) || !file.has(kArrivalTimes))
    throw InputError(file.path +
                     ": the checkpoint of this damage run has no crack-arrival table (it was written by an "
                     "mppm-solve without crack_path.csv); it cannot be continued bit for bit: run it again from "
                     "the start");
  model.crack_arrivals.restore(file.array<std::uint64_t>(kArrivalPoints), file.array<double>(kArrivalTimes),
                               model.points, point_count, file.path);
}

// The rows of the integrator's per-tracked-point arrays (body_force) across processes: the global
// row of each of this process's rows, and the process of every global row. Rows follow the tracked
// points' global ids, as in the one-process run.
struct TrackedRows {
  std::vector<std::int64_t> local_ids;
  std::vector<std::int32_t> owner;
  std::uint64_t count() const { return owner.size(); }
};

TrackedRows tracked_rows(const PointData& p, const ExplicitDynamics& dynamics, const CheckpointProcesses& processes) {
  TrackedRows rows;
  if (dynamics.tracks_all_points()) {
    rows.local_ids.assign(p.global_id.begin(), p.global_id.begin() + static_cast<std::ptrdiff_t>(p.owned));
    rows.owner.assign(processes.part_of.begin(), processes.part_of.end());
    return rows;
  }
  std::vector<std::int64_t> mine;
  for (const std::int32_t i : dynamics.tracked_points()) mine.push_back(p.global_id[static_cast<std::size_t>(i)]);
  const std::vector<std::vector<std::int64_t>> all = processes.group.gather(std::span<const std::int64_t>(mine));
  std::vector<std::pair<std::int64_t, std::int32_t>> merged;
  for (std::size_t r = 0; r < all.size(); ++r)
    for (const std::int64_t g : all[r]) merged.emplace_back(g, static_cast<std::int32_t>(r));
  std::sort(merged.begin(), merged.end());
  for (const auto& [g, r] : merged) rows.owner.push_back(r);
  for (const std::int64_t g : mine)
    rows.local_ids.push_back(std::lower_bound(merged.begin(), merged.end(), std::pair{g, std::int32_t{0}}) -
                             merged.begin());
  return rows;
}

// The values of rows [first, first + n) of an array of `width` values per row, as doubles (an
// integer array's values exactly: CheckpointArrayView::rows).
template <class T>
std::function<void(std::uint64_t, std::uint64_t, double*)> rows_as_doubles(const void* values, int width) {
  const auto* data = static_cast<const T*>(values);
  const auto w = static_cast<std::uint64_t>(width);
  return [data, w](std::uint64_t first, std::uint64_t n, double* out) {
    for (std::uint64_t k = 0; k < n * w; ++k) out[k] = static_cast<double>(data[first * w + k]);
  };
}

// A local array's rows as a gathered field's source (the element types a distributed run carries).
SnapshotFieldSource row_source(const CheckpointArrayView& a, std::size_t local_rows) {
  if (local_rows == 0 || a.count % local_rows != 0)
    throw std::logic_error("checkpoint array '" + a.name + "' cannot be written across processes");
  const auto width = static_cast<int>(a.count / local_rows);
  switch (a.element) {
    case CheckpointElement::f64:
      return {a.name, width, rows_as_doubles<double>(a.data, width)};
    case CheckpointElement::i32:
      return {a.name, width, rows_as_doubles<std::int32_t>(a.data, width)};
    case CheckpointElement::u8:
      return {a.name, width, rows_as_doubles<std::uint8_t>(a.data, width)};
    default:
      throw std::logic_error("checkpoint array '" + a.name + "' cannot be written across processes");
  }
}

// Where a gathered field goes: the array it fills and its whole model's rows.
struct GatheredArray {
  std::size_t array = 0;
  std::uint64_t rows = 0;
};

// The first process writes `arrays` (through `write`) with the carried arrays (the first
// `carried`) and body_force (the next) gathered from every process, a chunk of rows at a time: the
// per-point arrays by point, body_force by tracked point, a damage run's bond arrays by bond entry
// and by pair (BondRows); the others answer.
void write_gathered(std::vector<CheckpointArrayView>& arrays, std::size_t carried, const Model& model,
                    const ExplicitDynamics& dynamics, const CheckpointProcesses& processes,
                    const std::function<void()>& write) {
  const PointData& p = model.points;
  const TrackedRows tracked = tracked_rows(p, dynamics, processes);
  std::optional<BondRows> bond_rows;
  if (model.effects.damage) bond_rows.emplace(p, model.bonds, processes.part_of, processes.group);
  std::vector<GatheredRowSet> sets(2);
  std::vector<std::vector<GatheredArray>> targets(2);  // per set, per field
  sets[0].rows = {std::span<const std::int64_t>(p.global_id.data(), p.owned), owners_listed(processes.part_of)};
  for (std::size_t k = 0; k < carried; ++k) {
    const std::string& name = arrays[k].name;
    if (name == "bond_neighbor" || name == "bond_work") {
      sets.push_back(name == "bond_neighbor" ? bond_rows->entries() : bond_rows->pairs());
      targets.push_back({{k, name == "bond_neighbor" ? bond_rows->entry_count() : bond_rows->pair_count()}});
    } else {
      sets[0].local.push_back(row_source(arrays[k], p.owned + p.ghost));
      targets[0].push_back({k, processes.part_of.size()});
    }
  }
  sets[1].rows = {tracked.local_ids, owners_listed(tracked.owner)};
  const CheckpointArrayView& body_force = arrays[carried];
  // A process without tracked points has no rows to give (and no width to derive).
  sets[1].local.push_back(tracked.local_ids.empty() ? SnapshotFieldSource{body_force.name, p.dimension, {}}
                                                    : row_source(body_force, tracked.local_ids.size()));
  targets[1].push_back({carried, tracked.count()});
  with_gathered_row_sets(sets, processes.group, [&](const std::vector<std::vector<SnapshotFieldSource>>& gathered) {
    for (std::size_t set = 0; set < sets.size(); ++set)
      for (std::size_t field = 0; field < targets[set].size(); ++field) {
        const SnapshotFieldSource& s = gathered[set][field];
        CheckpointArrayView& a = arrays[targets[set][field].array];
        a.components = s.components;
        a.count = targets[set][field].rows * static_cast<std::uint64_t>(s.components);
        a.rows = s.values;
      }
    write();
  });
}

// A distributed run's restore: each per-point array's rows of this process's owned points (the
// ghosts' are fetched by every evaluation), and body_force's rows of its tracked points.
void restore_own_rows(const CheckpointFile& file, Model& model, const ExplicitDynamics& dynamics,
                      const CheckpointProcesses& processes, std::vector<double>& body_force) {
  PointData& p = model.points;
  const std::span<const std::int64_t> owned(p.global_id.data(), p.owned);
  const std::uint64_t points = processes.part_of.size();
  visit_carried_arrays(model, [&](const char* name, auto& values) {
    const std::string array = name;
    if (array == "bond_work") return;  // with the lists, below
    if (array == "bond_neighbor")
      restore_own_bonds(file.array<std::int32_t>(array), file.array<double>("bond_work"), p, model.bonds,
                        processes.group, file.path);
    else
      file.restore_rows(name, points, values.size() / (p.owned + p.ghost), owned, values);
  });
  if (model.effects.damage) {
    // The ghosts' shape terms and flags, and the last evaluation's displacement and rotation the
    // next bond-work increment reads at a pair's other end.
    share_shape_terms(p, true);
    p.ghost_source->update_ghosts(p.previous_displacement, p.dimension);
    if (!p.previous_rotation.empty()) p.ghost_source->update_ghosts(p.previous_rotation, p.rotation_components);
  }
  const TrackedRows tracked = tracked_rows(p, dynamics, processes);
  file.restore_rows("body_force", tracked.count(), static_cast<std::size_t>(p.dimension), tracked.local_ids,
                    body_force);
}

template <class T>
void add_vector(Fnv1a& h, const std::vector<T>& v) {
  const std::uint64_t n = v.size();
  h.add(&n, sizeof n);
  if (!v.empty()) h.add(v.data(), v.size() * sizeof(T));
}

}  // namespace

std::uint64_t point_cloud_fingerprint(const PointCloud& c) {
  Fnv1a h;
  const std::int64_t dimension = c.dimension;
  h.add(&dimension, sizeof dimension);
  for (double v : {c.spacing, c.horizon, c.thickness}) h.add(&v, sizeof v);
  for (const auto* v : {&c.x, &c.y, &c.z, &c.volume, &c.normal_x, &c.normal_y, &c.normal_z, &c.precrack_vertices})
    add_vector(h, *v);
  add_vector(h, c.region);
  add_vector(h, c.boundary_id);
  for (const auto& b : c.boundaries) {
    h.add(b.name + '\n' + b.type + '\n');
    h.add(&b.area, sizeof b.area);
    h.add(&b.point_count, sizeof b.point_count);
  }
  return h.h;
}

void write_checkpoint(const std::string& path, const RunIdentity& identity, const Model& model,
                      const ExplicitDynamics& dynamics, const RunLoopState& loop, bool simulate_write_failure,
                      const CheckpointProcesses* processes) {
  // The whole model's counts: over all processes in a distributed run.
  auto total = [&](std::uint64_t local) {
    return processes ? static_cast<std::uint64_t>(processes->group.total(static_cast<std::int64_t>(local))) : local;
  };
  CheckpointHeader header;
  header.dimension = model.dimension();
  header.point_count = total(model.points.owned);
  header.effects = checkpoint_effect_bits(model.effects);
  header.scene_fingerprint = identity.scene_fingerprint;
  header.points_fingerprint = identity.points_fingerprint;
  const ExplicitDynamics::Carried carried = dynamics.carried();
  header.step = carried.steps;
  header.time = carried.time;

  std::vector<CheckpointArrayView> arrays;
  visit_carried_arrays(model,
                       [&](const char* name, const auto& values) { arrays.push_back(checkpoint_array(name, values)); });
  // The arrays above are per point (a damage run's bond arrays per bond entry and per pair),
  // body_force per tracked point.
  const std::size_t carried_arrays = arrays.size();
  arrays.push_back(checkpoint_array("body_force", dynamics.body_force()));
  // Small arrays: built here, alive until the file is written.
  const std::vector<double> energy = energy_values(carried.energy);
  const std::vector<double> fluid_energy = fluid_energy_values(carried.energy);
  if (model.effects.pore_fluid) arrays.push_back(checkpoint_array("fluid_energy", fluid_energy));
  // The volumes through the fluid boundaries and their last rates (runs with such conditions only).
  if (!carried.fluid_boundary_flows.empty())
    arrays.push_back(checkpoint_array(kFluidBoundaries, carried.fluid_boundary_flows));
  const std::vector<double> integrator{carried.time, carried.initial_total, loop.time_step};
  const std::vector<std::uint64_t> model_counters{total(model.broken_bonds), total(model.detached_points),
                                                  total(model.unstable_detached_points),
                                                  total(model.energy_detached_points)};
  const std::vector<double> model_scalars{model.last_fracture_dissipation};
  // The crack-arrival table: every process's arrivals, merged in arrival order.
  const CrackArrivals::Table arrivals = model.effects.damage && processes
                                            ? model.crack_arrivals.whole_table(model.points, processes->group)
                                            : CrackArrivals::Table{};
  if (model.effects.damage) {
    arrays.push_back(checkpoint_array(kArrivalPoints, processes ? arrivals.points : model.crack_arrivals.points()));
    arrays.push_back(checkpoint_array(kArrivalTimes, processes ? arrivals.times : model.crack_arrivals.times()));
  }
  const std::vector<double> schedule{loop.next_row, loop.next_snapshot, loop.next_checkpoint, loop.worst_balance};
  const std::vector<double> guard{loop.guard.scale, loop.guard.last_plastic, loop.guard.last_fracture,
                                  loop.guard.created_plastic, loop.guard.created_fracture};
  const std::vector<std::uint64_t> tables{loop.load_table_bytes, loop.load_table_fingerprint, loop.energy_table_bytes,
                                          loop.energy_table_fingerprint};
  std::string snapshot_files;
  std::vector<std::int64_t> snapshot_steps;
  std::vector<double> snapshot_times;
  for (const auto& s : loop.snapshots) {
    snapshot_files += s.file + '\n';
    snapshot_steps.push_back(s.step);
    snapshot_times.push_back(s.time);
  }
  arrays.push_back(checkpoint_array("energy", energy));
  arrays.push_back(checkpoint_array("integrator", integrator));
  arrays.push_back(checkpoint_array("model_counters", model_counters));
  arrays.push_back(checkpoint_array("model_scalars", model_scalars));
  arrays.push_back(checkpoint_array("schedule", schedule));
  arrays.push_back(checkpoint_array("energy_guard", guard));
  arrays.push_back(checkpoint_array("tables", tables));
  arrays.push_back(checkpoint_text("snapshot_files", snapshot_files));
  arrays.push_back(checkpoint_array("snapshot_steps", snapshot_steps));
  arrays.push_back(checkpoint_array("snapshot_times", snapshot_times));
  arrays.push_back(checkpoint_text("points_file", loop.points_file));
  const auto write = [&] {
    std::error_code ec;
    std::filesystem::create_directories(std::filesystem::path(path).parent_path(), ec);
    if (ec) throw InputError(path + ": cannot create the checkpoint directory (" + ec.message() + ")");
    write_checkpoint_file(path, header, arrays, simulate_write_failure);
  };
  if (processes) {
    write_gathered(arrays, carried_arrays, model, dynamics, *processes, write);
  } else {
    write();
  }
}

RunLoopState restore_checkpoint(const CheckpointFile& file, const RunIdentity& identity, Model& model,
                                ExplicitDynamics& dynamics, const CheckpointProcesses* processes) {
  const CheckpointHeader& h = file.header;
  auto total = [&](std::uint64_t local) {
    return processes ? static_cast<std::uint64_t>(processes->group.total(static_cast<std::int64_t>(local))) : local;
  };
  const std::uint64_t points = total(model.points.owned);
  if (h.scene_fingerprint != identity.scene_fingerprint)
    throw InputError(file.path + ": the checkpoint was written for another scene (scene.resolved.yaml changed since)");
  if (h.points_fingerprint != identity.points_fingerprint)
    throw InputError(file.path + ": the checkpoint was written for other points (the points file changed since)");
  if (h.dimension != model.dimension() || h.point_count != points || h.effects != checkpoint_effect_bits(model.effects))
    throw InputError(file.path + ": the checkpoint is of a " + std::to_string(h.dimension) + "-D run with " +
                     std::to_string(h.point_count) + " points and other effects than this one");

  std::vector<double> body_force(dynamics.body_force().size());
  if (processes) {
    restore_own_rows(file, model, dynamics, *processes, body_force);
  } else {
    visit_carried_arrays(model, [&](const char* name, auto& values) {
      if (std::string(name) == "bond_neighbor")
        restore_broken_bonds(file, model.bonds);
      else
        file.restore(name, values);
    });
    file.restore("body_force", body_force);
  }
  const auto energy = scalars<double>(file, "energy", 8);
  const auto integrator = scalars<double>(file, "integrator", 3);
  ExplicitDynamics::Carried carried;
  carried.steps = h.step;
  carried.time = integrator[0];
  carried.initial_total = integrator[1];
  carried.energy = energy_from(energy);
  if (model.effects.pore_fluid) restore_fluid_energy(scalars<double>(file, "fluid_energy", 5), carried.energy);
  if (dynamics.has_fluid_boundaries())
    carried.fluid_boundary_flows =
        scalars<double>(file, kFluidBoundaries, dynamics.carried().fluid_boundary_flows.size());
  dynamics.restore(carried, body_force);

  const auto counters = scalars<std::uint64_t>(file, "model_counters", 4);
  if (processes) {
    // The counters are the whole model's, and each process keeps a share (bond_breakage.hpp) that
    // only the sums are read of: the first process takes them. The broken pairs and the detached
    // points must be those of the restored bonds and flags.
    std::uint64_t broken = 0, detached = 0;
    if (model.effects.damage) {
      const PointOrder order(model.points);
      const BondFamilies& f = model.bonds;
      for (std::size_t i = 0; i < model.points.owned; ++i) {
        detached += model.points.detached[i];
        for (std::int64_t b = f.offset[i]; b < f.offset[i + 1]; ++b)
          broken += !f.acting(b) && order(i) < order(f.neighbor_of(b));
      }
    } else {
      broken = model.broken_bonds;
      detached = model.detached_points;
    }
    if (counters[0] != total(broken) || counters[1] != total(detached))
      throw InputError(file.path + ": the checkpoint's broken bonds and detached points are not those of this model");
    const bool first = processes->group.rank() == 0;
    model.broken_bonds = first ? counters[0] : 0;
    model.detached_points = first ? counters[1] : 0;
    model.unstable_detached_points = first ? counters[2] : 0;
    model.energy_detached_points = first ? counters[3] : 0;
  } else {
    model.broken_bonds = counters[0];
    model.detached_points = counters[1];
    model.unstable_detached_points = counters[2];
    model.energy_detached_points = counters[3];
  }
  model.last_fracture_dissipation = scalars<double>(file, "model_scalars", 1)[0];
  if (model.effects.damage) restore_crack_arrivals(file, model, points);

  RunLoopState loop;
  loop.time_step = integrator[2];
  const auto schedule = scalars<double>(file, "schedule", 4);
  loop.next_row = schedule[0];
  loop.next_snapshot = schedule[1];
  loop.next_checkpoint = schedule[2];
  loop.worst_balance = schedule[3];
  const auto guard = scalars<double>(file, "energy_guard", 5);
  loop.guard = {guard[0], guard[1], guard[2], guard[3], guard[4]};
  const auto tables = scalars<std::uint64_t>(file, "tables", 4);
  loop.load_table_bytes = tables[0];
  loop.load_table_fingerprint = tables[1];
  loop.energy_table_bytes = tables[2];
  loop.energy_table_fingerprint = tables[3];
  const auto steps = file.array<std::int64_t>("snapshot_steps");
  const auto times = file.array<double>("snapshot_times");
  std::istringstream names(file.text("snapshot_files"));
  for (std::size_t k = 0; k < steps.size(); ++k) {
    std::string name;
    if (!std::getline(names, name) || k >= times.size())
      throw InputError(file.path + ": corrupted checkpoint (the snapshot list is incomplete)");
    loop.snapshots.push_back({name, steps[k], times[k]});
  }
  loop.points_file = file.text("points_file");
  return loop;
}

}  // namespace mppm::solver
