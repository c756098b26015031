// How much memory a run needs, known before anything big is allocated: printed by the
// preprocessor, checked by the solver against the memory this machine has available, so that a
// run that cannot fit is refused at once with the advice instead of being killed hours later.
#pragma once
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace mppm {

struct MemoryEstimateInput {
  std::uint64_t points = 0;  // all material points, boundary layers included
  // Bond entries (each bond is stored at both of its points). 0: estimated from the horizon
  // factor and the dimension with estimated_bond_entries().
  std::uint64_t bonds = 0;
  double horizon_factor = 3.0;  // delta / dx
  int dimension = 2;
  // Points with region > 0 or boundary_id > 0 (fictitious layers, loaded surfaces): the integrator
  // keeps the start-of-step state of those only, of every point with gravity or damping.
  std::uint64_t boundary_points = 0;
  bool damping = false;                      // numerics.damping != 0
  bool unsaturated = false;                  // material.pore_fluid.retention given
  std::vector<std::string> effects;          // scene effects: micropolar, damage, viscoplasticity, ...
  std::vector<std::string> snapshot_fields;  // scene output.fields
};

struct MemoryEstimate {
  std::uint64_t bonds = 0;            // bond entries used (given or estimated)
  std::uint64_t bytes_per_point = 0;  // the model's arrays and the points read from the file
  std::uint64_t bytes_per_bond = 0;
  std::uint64_t integrator_bytes = 0;  // the time integrator's start-of-step copies
  std::uint64_t snapshot_bytes = 0;    // the buffer a snapshot is written through
  std::uint64_t fixed_bytes = 0;       // program and libraries
  std::uint64_t total_bytes = 0;
};

// Lattice points j != 0 within horizon_factor spacings (the family of an interior point) times
// the points: every point of a regular lattice has at most this many bonds.
std::uint64_t estimated_bond_entries(std::uint64_t points, double horizon_factor, int dimension);

// Values per point of a snapshot field (solver/snapshot_fields.cpp) for the dimension D and the
// rotation components R (0 without micropolar); 0 for an unknown name.
std::uint64_t snapshot_field_components(const std::string& name, std::uint64_t D, std::uint64_t R);

MemoryEstimate estimate_run_memory(const MemoryEstimateInput& input);

// "1.23 GiB", "456 MiB", "789 KiB".
std::string format_memory(std::uint64_t bytes);

// MemAvailable of /proc/meminfo (bytes); nullopt where there is no such line (not Linux).
std::optional<std::uint64_t> available_memory_bytes(const std::string& meminfo_path = "/proc/meminfo");

// Throws InputError when the estimate exceeds `available_bytes`. `subject` starts the message
// (e.g. the scene file). The message gives the estimate, its parts and the advice, and then
// `more_advice` when given (e.g. ", or ...").
void require_memory_fits(const MemoryEstimate& estimate, std::uint64_t available_bytes, const std::string& subject,
                         const std::string& more_advice = "");

}  // namespace mppm
