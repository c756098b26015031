// A patch of a model: its points, their neighbours, the whole model's shape tensors and bonds.
#include "solver/model_patch.hpp"

#include <stdexcept>

#include "solver/internal_forces.hpp"

namespace mppm::solver {

namespace {

// The patch's points (within the radius) and their neighbours, in the model's order.
std::vector<std::size_t> patch_members(const Model& model, std::size_t centre, double radius,
                                       std::vector<std::uint8_t>& in_patch) {
  const PointData& p = model.points;
  const auto D = static_cast<std::size_t>(p.dimension);
  const double* c = &p.position[centre * D];
  in_patch.assign(p.owned, 0);
  std::vector<std::uint8_t> member(p.owned, 0);
  for (std::size_t i = 0; i < p.owned; ++i) {
    double r2 = 0.0;
    for (std::size_t a = 0; a < D; ++a) r2 += (p.position[i * D + a] - c[a]) * (p.position[i * D + a] - c[a]);
    if (r2 > radius * radius) continue;
    in_patch[i] = member[i] = 1;
    for (std::int64_t b = model.bonds.offset[i]; b < model.bonds.offset[i + 1]; ++b)
      member[model.bonds.neighbor_of(b)] = 1;
  }
  std::vector<std::size_t> members;
  for (std::size_t i = 0; i < p.owned; ++i)
    if (member[i]) members.push_back(i);
  return members;
}

// Copies the per-point values of `from`'s members into `to` (stride values per point).
template <class T>
void copy_members(const std::vector<T>& from, std::vector<T>& to, const std::vector<std::size_t>& members,
                  std::size_t stride) {
  to.resize(members.size() * stride);
  for (std::size_t s = 0; s < members.size(); ++s)
    for (std::size_t k = 0; k < stride; ++k) to[s * stride + k] = from[members[s] * stride + k];
}

}  // namespace

bool can_cut_patches(const Model& model) {
  return model.points.processes == nullptr && !model.effects.pore_fluid && !model.holds_history();
}

ModelPatch cut_patch(const Model& model, std::size_t centre, double radius) {
  if (!can_cut_patches(model)) throw std::logic_error("cut_patch: the model cannot be cut into patches");
  const PointData& p = model.points;
  const auto D = static_cast<std::size_t>(p.dimension);
  const auto R = static_cast<std::size_t>(p.rotation_components);
  std::vector<std::uint8_t> in_patch;
  const std::vector<std::size_t> members = patch_members(model, centre, radius, in_patch);
  ModelPatch out;
  // The operator at rest without history is the kernel without the history effects
  // (Model::linear_operator_kernel): the patch carries none of their state.
  EffectSet effects = model.effects;
  effects.damage = effects.viscoplasticity = false;
  PointCloud cloud;
  cloud.dimension = p.dimension;
  cloud.resize(members.size());
  for (std::size_t s = 0; s < members.size(); ++s) {
    const double* x = &p.position[members[s] * D];
    cloud.x[s] = x[0];
    cloud.y[s] = x[1];
    if (D == 3) cloud.z[s] = x[2];
    cloud.volume[s] = p.volume[members[s]];
    cloud.region[s] = p.region[members[s]];
  }
  Model& m = out.model;
  m.constants = model.constants;
  m.effects = effects;
  m.horizon = model.horizon;
  m.points = make_point_data(cloud, effects);
  const std::size_t symmetric = D * (D + 1) / 2;
  copy_members(p.shape_inverse, m.points.shape_inverse, members, symmetric);
  copy_members(p.stabilization_ck, m.points.stabilization_ck, members, symmetric);
  copy_members(p.detached, m.points.detached, members, 1);
  if (R > 0) copy_members(p.stabilization_rot, m.points.stabilization_rot, members, 1);
  std::vector<std::int32_t> index(p.owned, -1);
  for (std::size_t s = 0; s < members.size(); ++s) index[members[s]] = static_cast<std::int32_t>(s);
  BondFamilies& f = m.bonds;
  f.dimension = p.dimension;
  f.offset.assign(1, 0);
  for (const std::size_t i : members) {
    for (std::int64_t b = model.bonds.offset[i]; b < model.bonds.offset[i + 1]; ++b) {
      const std::int32_t j = index[model.bonds.neighbor_of(b)];
      if (j < 0) continue;
      f.neighbor.push_back(j);
      if (!model.bonds.xi.empty())
        for (std::size_t a = 0; a < D; ++a) f.xi.push_back(model.bonds.xi[static_cast<std::size_t>(b) * D + a]);
    }
    f.offset.push_back(static_cast<std::int64_t>(f.neighbor.size()));
  }
  m.kernel = internal_force_functions(p.dimension, effects);
  out.inside.resize(members.size());
  for (std::size_t s = 0; s < members.size(); ++s) out.inside[s] = in_patch[members[s]];
  for (const std::uint8_t v : out.inside) out.points_inside += v;
  return out;
}

}  // namespace mppm::solver
