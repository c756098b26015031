// The memory model of a run: the solver's arrays (solver/point_data.hpp, bond_families.hpp,
// explicit_dynamics.hpp) counted per point and per bond, plus one snapshot and the program.
#include "common/memory_estimate.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "common/input_error.hpp"
#include "common/lattice_offsets.hpp"
#include "common/snapshot_file.hpp"

namespace mppm {
namespace {

bool has(const std::vector<std::string>& list, const char* name) {
  return std::find(list.begin(), list.end(), name) != list.end();
}

// Resident size of mppm-solve apart from the run's arrays: the C++ runtime, OpenMP, MPI, VTK,
// yaml-cpp and their data, and the partly used huge pages of malloc's arenas
// (solver/huge_page_allocation.cpp: 2 MiB each, one more arena with a second thread). Measured
// peak RSS on Debian 12 (2026-12-07): 16.3 MiB for `mppm-solve --help`, 18.3-19.0 MiB for a
// 1000-point run, 21 MiB for the 4000-point quickstart plate; larger runs up to 2.5 MiB beyond
// their arrays and 20 MiB at two threads (tests/unit/test_memory_estimate.cpp,
// workflows/accuracy-cost/estimates.md). So 22 MiB.
constexpr std::uint64_t kProgramBytes = 22ull << 20;

}  // namespace

// Values per point of a snapshot field (solver/snapshot_fields.cpp); 0 for an unknown name.
std::uint64_t snapshot_field_components(const std::string& name, std::uint64_t D, std::uint64_t R) {
  if (name == "displacement" || name == "velocity") return D;
  if (name == "rotation" || name == "rotation_rate") return R;
  if (name == "strain") return D * D;
  if (name == "wryness" || name == "couple_stress") return R * D;
  if (name == "stress" || name == "plastic_strain") return 9;
  if (name == "porosity" || name == "plastic_shear_strain" || name == "equivalent_plastic_strain" ||
      name == "detached" || name == "damage" || name == "crack_area" || name == "pore_pressure" ||
      name == "fluid_content" || name == "saturation")
    return 1;
  if (name == "darcy_velocity") return D;
  return 0;
}

std::uint64_t estimated_bond_entries(std::uint64_t points, double horizon_factor, int dimension) {
  if (!(horizon_factor > 0) || horizon_factor > 50) return 0;
  return points * static_cast<std::uint64_t>(family_offset_count(dimension, horizon_factor));
}

MemoryEstimate estimate_run_memory(const MemoryEstimateInput& in) {
  const std::uint64_t D = in.dimension == 3 ? 3 : 2;
  // Rotation components: the micro-rotation arrays exist with micropolar only.
  const std::uint64_t R = has(in.effects, "micropolar") ? (D == 3 ? 3 : 1) : 0;
  const std::uint64_t S = D * (D + 1) / 2;  // a symmetric tensor, packed
  const bool damage = has(in.effects, "damage");
  const bool viscoplastic = has(in.effects, "viscoplasticity");
  MemoryEstimate e;
  e.bonds = in.bonds ? in.bonds : estimated_bond_entries(in.points, in.horizon_factor, in.dimension);

  // Bytes per point, array by array (8 per double, 4 per int32, 1 per flag): solver/point_data.hpp,
  // bond_families.hpp, boundary_conditions.hpp. The points as read are released when the model is
  // built, before its bonds exist, so they are not part of the peak.
  std::uint64_t p = 0;
  p += 8 * D + 8 + 4 + 4;                         // reference position, volume, region, boundary id
  p += 3 * 8 * D;                                 // displacement, velocity, force
  p += 2 * 8 * S + 1;                             // K^-1, C:K^-1, detached
  p += 2 * 8 * D * D;                             // strain, force tensor A
  p += 8;                                         // stabilization energy
  if (R > 0) p += 3 * 8 * R + 8 + 2 * 8 * R * D;  // rotation, spin, moment, g = G_s B_w tr K^-1 / d, wryness, Q
  p += 8;                                         // bond offsets (CSR)
  p += 1;                                         // prescribed-component bits of the boundary conditions
  // The cell list of the family search while the bonds are filled: its point list and the cells'
  // starts (one cell per horizon cube, a few points each: 1 B per point rounded up).
  p += 4 + 1;
  // no-fail, broken count, the previous evaluation's displacement and rotation and the sums of its
  // force / moment tensors with this one's (the bond work's trapezoid rule), the offsets of the bond pairs (the family
  // volumes of the few points next to a pre-crack are left out), the crack-arrival flag (the
  // arrivals themselves, 16 B per point on the crack path, are left out too)
  if (damage) p += 1 + 4 + 8 * D + 8 * R + 8 * D * D + 8 * R * D + 8 + 1;
  if (viscoplastic) p += 9 * 8 + 8 * R * D + 2 * 8 + 1;  // plastic strain and wryness, ebar, dissipation, active
  // Pore fluid: pressure, fluid content change, its rate, the pressures a flow update starts from,
  // and the RKL2 super step's start contents and rates and its two increments (counted always: an upper
  // bound by 32 B per point for the runs whose flow needs no super step).
  if (has(in.effects, "pore_fluid")) p += 4 * 8 + 4 * 8;
  // Unsaturated: the stored fluid energy and k_r per point, the change of Bishop's pore stress of a
  // force correction and the k_r of the flow's limit (both made per update).
  if (has(in.effects, "pore_fluid") && in.unsaturated) p += 4 * 8;
  e.bytes_per_point = p;

  // The integrator (solver/explicit_dynamics.hpp), per tracked point: body force and its previous
  // value, force, moment, displacement and rotation at the step's start, the work increment; and
  // when they are not all points, their indices and the rows of the loaded ones (4 B each).
  const bool track_all = in.damping || has(in.effects, "gravity");
  const std::uint64_t tracked = track_all ? in.points : std::min(in.boundary_points, in.points);
  e.integrator_bytes = tracked * (8 * (4 * D + 2 * R + 1) + (track_all ? 0 : 4 + 4));

  // Per bond entry: the neighbour index (the bond vector comes from the positions; a broken bond is
  // marked in it); with damage also half the bond work, which is stored once per pair of entries
  // (solver/model.cpp allocates it only then).
  e.bytes_per_bond = 4 + (damage ? 4 : 0);

  // Snapshots are written a chunk of points at a time (common/snapshot_file.hpp), one field after
  // the other: the buffer of the widest field (the reference snapshot's position has 3).
  std::uint64_t components = 3;
  for (const std::string& f : in.snapshot_fields) components = std::max(components, snapshot_field_components(f, D, R));
  e.snapshot_bytes = components * 8 * std::min<std::uint64_t>(in.points, kSnapshotPointsPerChunk);

  e.fixed_bytes = kProgramBytes;
  e.total_bytes = e.fixed_bytes + in.points * e.bytes_per_point + e.bonds * e.bytes_per_bond + e.integrator_bytes +
                  e.snapshot_bytes;
  return e;
}

std::string format_memory(std::uint64_t bytes) {
  const double b = static_cast<double>(bytes);
  char text[32];
  if (b >= 1024.0 * 1024 * 1024)
    std::snprintf(text, sizeof text, "%.2f GiB", b / (1024.0 * 1024 * 1024));
  else if (b >= 1024.0 * 1024)
    std::snprintf(text, sizeof text, "%.0f MiB", b / (1024.0 * 1024));
  else
    std::snprintf(text, sizeof text, "%.0f KiB", b / 1024.0);
  return text;
}

std::optional<std::uint64_t> available_memory_bytes(const std::string& meminfo_path) {
  std::ifstream in(meminfo_path);
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind("MemAvailable:", 0) != 0) continue;
    std::istringstream fields(line.substr(13));
    std::uint64_t kib = 0;
    std::string unit;
    if (fields >> kib >> unit && unit == "kB") return kib * 1024;
    return std::nullopt;
  }
  return std::nullopt;
}

void require_memory_fits(const MemoryEstimate& e, std::uint64_t available_bytes, const std::string& subject,
                         const std::string& more_advice) {
  if (e.total_bytes <= available_bytes) return;
  std::ostringstream s;
  s << subject << ": the run needs about " << format_memory(e.total_bytes) << " of memory but only "
    << format_memory(available_bytes) << " is available (points "
    << format_memory(e.total_bytes - e.fixed_bytes - e.snapshot_bytes - e.bonds * e.bytes_per_bond) << ", " << e.bonds
    << " bond entries " << format_memory(e.bonds * e.bytes_per_bond) << ", one snapshot "
    << format_memory(e.snapshot_bytes)
    << "); use a coarser geometry.spacing (memory falls with its square in "
       "2-D, its cube in 3-D), a smaller horizon_factor, or fewer output.fields"
    << more_advice;
  throw InputError(s.str());
}

}  // namespace mppm
