// Run under mpirun with 1 to 4 processes (tests/mpi.cmake): the force kernel on a partitioned
// lattice, each process holding its part and its ghosts and exchanging the ghosts' displacement,
// rotation, shape-tensor terms and pass-1 tensors (solver/halo_exchange.hpp), gives every owned
// point the force, moment and stabilization energy of the one-process model to the last bit.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "solver/bond_families.hpp"
#include "solver/ghost_exchange.hpp"
#include "solver/halo_exchange.hpp"
#include "solver/horizon_search.hpp"
#include "solver/internal_forces.hpp"
#include "solver/local_points.hpp"
#include "solver/model.hpp"
#include "solver/process_group.hpp"
#include "solver/shape_tensor.hpp"
#include "tests/verification/problems/generic_scene.hpp"
#include "tests/verification/problems/periodic_lattice.hpp"

namespace {

using namespace mppm;
using namespace mppm::solver;

// A displacement and rotation field of every point from its global id and position: a smooth part
// (strain of 1e-3) and a pseudo-random part of the same size, so that every bond is strained
// differently.
double field_value(std::int64_t id, int component, double x) {
  std::uint64_t h = static_cast<std::uint64_t>(id) * 0x9E3779B97F4A7C15ull + static_cast<std::uint64_t>(component + 7);
  h ^= h >> 29;
  h *= 0xBF58476D1CE4E5B9ull;
  h ^= h >> 32;
  const double noise = static_cast<double>(h >> 11) * 0x1.0p-53 - 0.5;
  return 1e-3 * x * (component + 1) + 1e-6 * noise;
}

void set_field(PointData& p, std::size_t points, const std::vector<std::int64_t>& id) {
  const int D = p.dimension, R = p.rotation_components;
  for (std::size_t i = 0; i < points; ++i) {
    const std::int64_t g = id.empty() ? static_cast<std::int64_t>(i) : id[i];
    for (int c = 0; c < D; ++c) p.displacement[i * D + c] = field_value(g, c, p.position[i * D]);
    for (int c = 0; c < R; ++c) p.rotation[i * R + c] = 1e-3 * field_value(g, D + c, p.position[i * D + 1]);
  }
}

std::uint64_t bits(double x) { return std::bit_cast<std::uint64_t>(x); }

struct Case {
  std::string name;
  int dimension;
  std::array<int, 3> n;
  bool micropolar;
};

// This process's part of a lattice: its points (owned, then ghosts) with their families, the ghosts'
// shape terms and the field of set_field, and the halo that fetches the ghosts' values.
struct LocalPart {
  std::unique_ptr<HaloExchange> halo;
  PointData p;
  BondFamilies f;
};

LocalPart local_part(const PointCloud& cloud, const ModelOptions& o, const ProcessGroup& group) {
  const int D = cloud.dimension;
  const double reach = bond_reach(o.horizon, o.spacing);
  const std::vector<double> x = cloud_positions(cloud);
  const PointPositions positions{D, x.data(), cloud.size()};
  const std::vector<std::int32_t> part = partition_cloud(positions, reach, o.spacing, group.size());
  const LocalPoints local = local_points(positions, part, group.rank(), reach, o.spacing);
  LocalPart l{std::make_unique<HaloExchange>(local, part), make_local_point_data(cloud, local, o.effects), {}};
  PointData& p = l.p;
  p.ghost_source = l.halo.get();
  FamilyOptions fo;
  fo.horizon = o.horizon;
  fo.spacing = o.spacing;
  l.f = build_families(p, fo);
  update_shape_tensors(p, l.f, o.constants);
  l.halo->update_ghosts(p.stabilization_ck, D * (D + 1) / 2);
  if (o.effects.micropolar) l.halo->update_ghosts(p.stabilization_rot, 1);
  set_field(p, p.owned, p.global_id);
  return l;
}

void expect_distributed_forces_equal_whole(const Case& k) {
  const ProcessGroup group = ProcessGroup::world();
  const double dx = 1e-3;
  const Scene scene = verification::make_scene(k.dimension, k.micropolar, dx, 3.05);
  const PointCloud cloud = verification::make_lattice(k.dimension, k.n, dx, scene.thickness);
  const ModelOptions o = model_options(scene);
  const int D = k.dimension;

  // The one-process model, on every process.
  Model whole = verification::make_model(cloud, scene);
  set_field(whole.points, whole.points.owned, {});
  whole.kernel.forces_and_energy(whole.points, whole.bonds, whole.constants, nullptr);

  // This process's part (the force pass fetches the ghosts' displacement and rotation).
  LocalPart part = local_part(cloud, o, group);
  PointData& p = part.p;
  const HaloExchange& halo = *part.halo;
  const BondFamilies& f = part.f;
  const InternalForceFunctions kernel = internal_force_functions(D, o.effects);
  kernel.forces_and_energy(p, part.f, o.constants, nullptr);

  // Every ghost is a neighbour of an owned point, and every owned point's bonds are the whole
  // model's.
  EXPECT_EQ(halo.points_received(), p.ghost) << k.name;
  if (group.size() > 1) {
    EXPECT_GT(halo.neighbours(), 0u) << k.name;
  }
  const int R = p.rotation_components;
  std::size_t differing = 0;
  for (std::size_t i = 0; i < p.owned; ++i) {
    const auto g = static_cast<std::size_t>(p.global_id[i]);
    ASSERT_EQ(f.offset[i + 1] - f.offset[i], whole.bonds.offset[g + 1] - whole.bonds.offset[g]) << k.name;
    for (int c = 0; c < D; ++c) differing += bits(p.force[i * D + c]) != bits(whole.points.force[g * D + c]);
    for (int c = 0; c < R; ++c) differing += bits(p.moment[i * R + c]) != bits(whole.points.moment[g * R + c]);
    differing += bits(p.stabilization_energy[i]) != bits(whole.points.stabilization_energy[g]);
  }
  EXPECT_EQ(differing, 0u) << k.name << ", process " << group.rank() << " of " << group.size() << ": " << p.owned
                           << " owned, " << p.ghost << " ghosts";
  // The owned points add up to the lattice.
  EXPECT_EQ(group.sum(ExactSum(static_cast<double>(p.owned))), static_cast<double>(cloud.size())) << k.name;
}

TEST(MpiForces, MicropolarPlateGivesTheOneProcessBits) {
  expect_distributed_forces_equal_whole({"2-D micro-polar 30 x 20", 2, {30, 20, 1}, true});
}

TEST(MpiForces, NonPolarPlateGivesTheOneProcessBits) {
  expect_distributed_forces_equal_whole({"2-D non-polar 30 x 20", 2, {30, 20, 1}, false});
}

// 4 processes on 12 columns: parts 3 columns wide, thinner than the horizon (3.05 spacings), so
// ghosts come from parts beyond the adjacent ones.
TEST(MpiForces, PartsThinnerThanTheHorizonGiveTheOneProcessBits) {
  expect_distributed_forces_equal_whole({"2-D strip 12 x 4", 2, {12, 4, 1}, true});
}

TEST(MpiForces, MicropolarBlockGivesTheOneProcessBits) {
  expect_distributed_forces_equal_whole({"3-D micro-polar 9 x 8 x 7", 3, {9, 8, 7}, true});
}

// Forwards to the halo and, when the first exchange (pass 1's displacement and rotation) is
// finished, records which owned points already have their pass-1 force tensor.
class WatchedExchange final : public GhostExchange {
 public:
  WatchedExchange(const HaloExchange& halo, const PointData& p) : halo_(halo), p_(p) {}
  void update_ghosts(std::vector<double>& values, int components) const override {
    halo_.update_ghosts(values, components);
  }
  std::vector<PointNote> notify_owners(std::span<const PointNote> notes) const override {
    return halo_.notify_owners(notes);
  }
  void begin_update(std::vector<double>& values, int components) const override {
    halo_.begin_update(values, components);
  }
  void advance_transfers() const override { halo_.advance_transfers(); }
  void finish_updates() const override {
    if (computed_before_first_finish.empty()) {
      const std::size_t dd = static_cast<std::size_t>(p_.dimension * p_.dimension);
      for (std::size_t i = 0; i < p_.owned; ++i)
        computed_before_first_finish.push_back(!std::isnan(p_.force_tensor[i * dd]));
    }
    halo_.finish_updates();
  }
  mutable std::vector<bool> computed_before_first_finish;

 private:
  const HaloExchange& halo_;
  const PointData& p_;
};

// The overlap: the interior points (no ghost in their families) get their pass-1 tensors while the
// ghosts' displacement and rotation travel, the border points only after they arrived.
TEST(MpiForces, TheInteriorIsComputedWhileTheGhostsTravel) {
  const ProcessGroup group = ProcessGroup::world();
  const Scene scene = verification::make_scene(2, true, 1e-3, 3.05);
  const PointCloud cloud = verification::make_lattice(2, {30, 20, 1}, 1e-3, scene.thickness);
  const ModelOptions o = model_options(scene);
  LocalPart part = local_part(cloud, o, group);
  PointData& p = part.p;
  const BondFamilies& f = part.f;
  if (group.size() == 1) {
    EXPECT_TRUE(f.interior_points.empty() && f.border_points.empty());
    return;
  }
  // The split: every owned point once, ascending in each list; an interior point's neighbours are
  // all owned, a border point has a ghost among them; a part of the 30 x 20 plate has both kinds.
  ASSERT_EQ(f.interior_points.size() + f.border_points.size(), p.owned);
  EXPECT_TRUE(std::is_sorted(f.interior_points.begin(), f.interior_points.end()));
  EXPECT_TRUE(std::is_sorted(f.border_points.begin(), f.border_points.end()));
  EXPECT_FALSE(f.interior_points.empty());
  EXPECT_FALSE(f.border_points.empty());
  auto has_ghost = [&](std::size_t i) {
    for (std::int64_t b = f.offset[i]; b < f.offset[i + 1]; ++b)
      if (f.neighbor_of(b) >= p.owned) return true;
    return false;
  };
  for (const std::size_t i : f.interior_points) EXPECT_FALSE(has_ghost(i)) << i;
  for (const std::size_t i : f.border_points) EXPECT_TRUE(has_ghost(i)) << i;

  const WatchedExchange watched(*part.halo, p);
  p.ghost_source = &watched;
  std::fill(p.force_tensor.begin(), p.force_tensor.end(), std::nan(""));
  internal_force_functions(2, o.effects).forces(p, part.f, o.constants, nullptr);
  ASSERT_EQ(watched.computed_before_first_finish.size(), p.owned);
  for (const std::size_t i : f.interior_points) EXPECT_TRUE(watched.computed_before_first_finish[i]) << i;
  for (const std::size_t i : f.border_points) EXPECT_FALSE(watched.computed_before_first_finish[i]) << i;
}

}  // namespace
