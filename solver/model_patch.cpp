// A patch of a model: its points, their neighbours, the whole model's shape tensors and bonds,
// gathered from every process that holds some of them.
#include "solver/model_patch.hpp"

#include <algorithm>
#include <bit>
#include <limits>
#include <span>
#include <stdexcept>

#include "solver/internal_forces.hpp"

namespace mppm::solver {

namespace {

bool within(const PointData& p, std::size_t i, const std::array<double, 3>& centre, double radius) {
  const auto D = static_cast<std::size_t>(p.dimension);
  double r2 = 0.0;
  for (std::size_t a = 0; a < D; ++a) r2 += (p.position[i * D + a] - centre[a]) * (p.position[i * D + a] - centre[a]);
  return r2 <= radius * radius;
}

// One process's points of the patch (its own points within the radius, and its own points with a
// neighbour within it: families are symmetric, so these are the neighbours of the patch's points),
// as a flat record per point that every process can read: the global id, whether it is inside,
// its region, detached flag and bond count, its position, volume, shape tensors (as bits), then
// each bond's neighbour by global id (and bond vector, on a periodic lattice).
std::vector<std::int64_t> own_piece(const Model& model, const std::array<double, 3>& centre, double radius) {
  const PointData& p = model.points;
  const BondFamilies& f = model.bonds;
  const auto D = static_cast<std::size_t>(p.dimension);
  const auto R = static_cast<std::size_t>(p.rotation_components);
  const std::size_t symmetric = D * (D + 1) / 2;
  const bool periodic = !f.xi.empty();
  auto bits = [](double v) { return std::bit_cast<std::int64_t>(v); };
  // A point farther than the radius and a bond's reach from the centre has no neighbour within the
  // radius (on a periodic lattice a bond may wrap around, so there every point is looked at).
  const double reach = periodic ? std::numeric_limits<double>::infinity() : radius + 1.01 * model.horizon;
  std::vector<std::int64_t> out;
  for (std::size_t i = 0; i < p.owned; ++i) {
    if (!within(p, i, centre, reach)) continue;
    const bool inside = within(p, i, centre, radius);
    bool member = inside;
    for (std::int64_t b = f.offset[i]; !member && b < f.offset[i + 1]; ++b)
      member = within(p, f.neighbor_of(b), centre, radius);
    if (!member) continue;
    out.insert(out.end(), {p.global_index(i), std::int64_t{inside}, std::int64_t{p.region[i]},
                           std::int64_t{p.detached[i]}, f.offset[i + 1] - f.offset[i]});
    for (std::size_t a = 0; a < D; ++a) out.push_back(bits(p.position[i * D + a]));
    out.push_back(bits(p.volume[i]));
    for (std::size_t k = 0; k < symmetric; ++k) out.push_back(bits(p.shape_inverse[i * symmetric + k]));
    for (std::size_t k = 0; k < symmetric; ++k) out.push_back(bits(p.stabilization_ck[i * symmetric + k]));
    if (R > 0) out.push_back(bits(p.stabilization_rot[i]));
    for (std::int64_t b = f.offset[i]; b < f.offset[i + 1]; ++b) {
      out.push_back(p.global_index(f.neighbor_of(b)));
      if (periodic)
        for (std::size_t a = 0; a < D; ++a) out.push_back(bits(f.xi[static_cast<std::size_t>(b) * D + a]));
    }
  }
  return out;
}

// Where each point's record starts in the gathered pieces, in the order of the global ids.
struct RecordIndex {
  const std::int64_t* start;
  std::int64_t id() const { return start[0]; }
};

std::vector<RecordIndex> index_records(const std::vector<std::vector<std::int64_t>>& pieces, std::size_t D,
                                       std::size_t R, bool periodic) {
  const std::size_t symmetric = D * (D + 1) / 2;
  const std::size_t fixed = 5 + D + 1 + 2 * symmetric + (R > 0 ? 1 : 0);
  const std::size_t per_bond = 1 + (periodic ? D : 0);
  std::vector<RecordIndex> records;
  for (const auto& piece : pieces)
    for (std::size_t at = 0; at < piece.size();) {
      records.push_back({piece.data() + at});
      at += fixed + static_cast<std::size_t>(piece[at + 4]) * per_bond;
    }
  std::sort(records.begin(), records.end(), [](const RecordIndex& a, const RecordIndex& b) { return a.id() < b.id(); });
  return records;
}

ModelPatch assemble_patch(const Model& model, const std::vector<std::vector<std::int64_t>>& pieces) {
  const PointData& p = model.points;
  const auto D = static_cast<std::size_t>(p.dimension);
  const auto R = static_cast<std::size_t>(p.rotation_components);
  const std::size_t symmetric = D * (D + 1) / 2;
  const bool periodic = !model.bonds.xi.empty();
  const std::vector<RecordIndex> records = index_records(pieces, D, R, periodic);
  auto real = [](std::int64_t v) { return std::bit_cast<double>(v); };
  ModelPatch out;
  // The operator at rest without history is the kernel without the history effects
  // (Model::linear_operator_kernel): the patch carries none of their state.
  EffectSet effects = model.effects;
  effects.damage = effects.viscoplasticity = false;
  PointCloud cloud;
  cloud.dimension = p.dimension;
  cloud.resize(records.size());
  for (std::size_t s = 0; s < records.size(); ++s) {
    const std::int64_t* r = records[s].start;
    cloud.x[s] = real(r[5]);
    cloud.y[s] = real(r[6]);
    if (D == 3) cloud.z[s] = real(r[7]);
    cloud.volume[s] = real(r[5 + D]);
    cloud.region[s] = static_cast<std::int32_t>(r[2]);
  }
  Model& m = out.model;
  m.constants = model.constants;
  m.effects = effects;
  m.horizon = model.horizon;
  m.points = make_point_data(cloud, effects);
  PointData& q = m.points;
  q.shape_inverse.resize(records.size() * symmetric);
  q.stabilization_ck.resize(records.size() * symmetric);
  q.detached.resize(records.size());
  if (R > 0) q.stabilization_rot.resize(records.size());
  out.inside.resize(records.size());
  std::vector<std::int64_t> ids(records.size());
  for (std::size_t s = 0; s < records.size(); ++s) ids[s] = records[s].id();
  BondFamilies& f = m.bonds;
  f.dimension = p.dimension;
  f.offset.assign(1, 0);
  for (std::size_t s = 0; s < records.size(); ++s) {
    const std::int64_t* r = records[s].start;
    out.inside[s] = static_cast<std::uint8_t>(r[1]);
    q.detached[s] = static_cast<std::uint8_t>(r[3]);
    const std::int64_t* values = r + 5 + D + 1;
    for (std::size_t k = 0; k < symmetric; ++k) q.shape_inverse[s * symmetric + k] = real(values[k]);
    for (std::size_t k = 0; k < symmetric; ++k) q.stabilization_ck[s * symmetric + k] = real(values[symmetric + k]);
    if (R > 0) q.stabilization_rot[s] = real(values[2 * symmetric]);
    const std::int64_t* bond = values + 2 * symmetric + (R > 0 ? 1 : 0);
    for (std::int64_t b = 0; b < r[4]; ++b, bond += 1 + (periodic ? D : 0)) {
      const auto found = std::lower_bound(ids.begin(), ids.end(), bond[0]);
      if (found == ids.end() || *found != bond[0]) continue;  // a neighbour's neighbour outside the patch
      f.neighbor.push_back(static_cast<std::int32_t>(found - ids.begin()));
      if (periodic)
        for (std::size_t a = 0; a < D; ++a) f.xi.push_back(real(bond[1 + a]));
    }
    f.offset.push_back(static_cast<std::int64_t>(f.neighbor.size()));
  }
  m.kernel = internal_force_functions(p.dimension, effects);
  for (const std::uint8_t v : out.inside) out.points_inside += v;
  return out;
}

}  // namespace

bool can_cut_patches(const Model& model) {
  double history = model.holds_history() ? 1.0 : 0.0;
  if (model.points.processes) history = model.points.processes->highest(history);
  return !model.effects.pore_fluid && history == 0.0;
}

PatchCentre patch_centre(const Model& model, const StiffestPoint& own) {
  const PointData& p = model.points;
  const auto D = static_cast<std::size_t>(p.dimension);
  PatchCentre c;
  if (!p.processes) {
    c.block_eigenvalue = own.block_eigenvalue;
    if (own.block_eigenvalue > 0.0)
      for (std::size_t a = 0; a < D; ++a) c.position[a] = p.position[own.index * D + a];
    return c;
  }
  const ProcessGroup& g = *p.processes;
  c.block_eigenvalue = g.highest(own.block_eigenvalue);
  if (!(c.block_eigenvalue > 0.0)) return c;
  constexpr std::int64_t none = std::numeric_limits<std::int64_t>::max();
  const bool mine = own.block_eigenvalue == c.block_eigenvalue;
  const std::int64_t chosen = g.lowest(mine ? p.global_index(own.index) : none);
  std::vector<std::int64_t> position;
  if (mine && p.global_index(own.index) == chosen)
    for (std::size_t a = 0; a < D; ++a) position.push_back(std::bit_cast<std::int64_t>(p.position[own.index * D + a]));
  for (const auto& from : g.gather(std::span<const std::int64_t>(position)))
    if (!from.empty())
      for (std::size_t a = 0; a < D; ++a) c.position[a] = std::bit_cast<double>(from[a]);
  return c;
}

ModelPatch cut_patch(const Model& model, const std::array<double, 3>& centre, double radius) {
  if (!can_cut_patches(model)) throw std::logic_error("cut_patch: the model cannot be cut into patches");
  std::vector<std::int64_t> own = own_piece(model, centre, radius);
  if (!model.points.processes) return assemble_patch(model, {std::move(own)});
  return assemble_patch(model, model.points.processes->gather(std::span<const std::int64_t>(own)));
}

std::size_t model_points(const Model& model) {
  const PointData& p = model.points;
  return p.processes ? static_cast<std::size_t>(p.processes->total(static_cast<std::int64_t>(p.owned))) : p.owned;
}

}  // namespace mppm::solver
