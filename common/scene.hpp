// The scene: one YAML file that describes a simulation completely (docs/scene.md).
// Everything here is resolved: SI units, every default filled in, paths absolute.
#pragma once
#include <array>
#include <cstddef>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace mppm {

// The effects a scene can call for (docs/theory.md section 10).
struct EffectSet {
  bool micropolar = false;
  bool viscoplasticity = false;
  bool damage = false;
  bool gravity = false;
  bool pore_fluid = false;  // saturated pore fluid in the pores (docs/theory.md section 12)

  std::vector<std::string> names() const;  // in canonical order
  friend bool operator==(const EffectSet&, const EffectSet&) = default;
};

// Which part of the boundary (or which pre-crack) an entry means: a physical group name,
// gmsh entity tags, or the boundary of the body inside an axis-aligned box (SI metres).
struct Selector {
  std::string physical_group;                               // empty if not used
  std::vector<int> entities;                                // empty if not used
  std::optional<std::array<std::array<double, 3>, 2>> box;  // [[x0,y0,z0],[x1,y1,z1]]

  std::string describe() const;  // "top", "entities [12, 15]", "box [[..],[..]]"
  // The same with every digit of the box corners (round trip): equal strings, equal selections.
  std::string fingerprint() const;
};

// A piecewise-linear history of a vector value, held constant outside its table.
// Constant values have one row; `ramp: t0` gives rows (0, 0) and (t0, value).
struct History {
  std::vector<double> times;                // strictly increasing
  std::vector<std::vector<double>> values;  // values[row][component]

  std::vector<double> at(double t) const;
  double component_at(double t, std::size_t c) const;
};

// pore_pressure (a drained boundary) and fluid_flux (an inflow) act on the pore fluid only
// (docs/theory.md section 12).
enum class BoundaryType { velocity, displacement, traction, pressure, pore_pressure, fluid_flux };
const char* to_string(BoundaryType type);

// True for conditions carried by a fictitious layer outside the body (docs/theory.md section 8).
inline bool is_kinematic(BoundaryType type) {
  return type == BoundaryType::velocity || type == BoundaryType::displacement;
}
// True for the pore fluid's conditions (the effect pore_fluid only).
inline bool is_fluid(BoundaryType type) {
  return type == BoundaryType::pore_pressure || type == BoundaryType::fluid_flux;
}
// True for conditions carried by the body points within a loaded depth of the boundary
// (BoundaryCondition::traction_depth); the others have a layer as deep as the horizon outside it.
inline bool has_loaded_depth(BoundaryType type) {
  return type == BoundaryType::traction || type == BoundaryType::pressure || type == BoundaryType::fluid_flux;
}
// The number of components of a condition's value: one for a pressure, a pore pressure and a
// fluid flux (inflow per unit area), d otherwise.
inline std::size_t value_components(BoundaryType type, int dimension) {
  return type == BoundaryType::pressure || is_fluid(type) ? 1 : static_cast<std::size_t>(dimension);
}

struct BoundaryCondition {
  std::string name;  // label used in load.csv, POINTS.vtp and summaries
  Selector selector;
  BoundaryType type = BoundaryType::traction;
  // Components (value_components: d of them; 1 for pressure, pore_pressure and fluid_flux). For
  // kinematic conditions a component may be free (not prescribed): constrained[c] == false.
  History value;
  std::vector<bool> constrained;
  // Micro-rotation condition on a kinematic layer (micropolar only): rotation rate
  // (velocity type) or rotation (displacement type); 1 component in 2-D, 3 in 3-D.
  std::optional<History> rotation;
  double traction_depth = 0.0;  // traction/pressure/fluid_flux: depth of the loaded layer [m] (default dx)
  int line = 0;                 // line in the scene file, for messages
};

// How w_cr follows from G_cr (solver/bond_breakage.hpp): `lattice` (the bonds of the lattice that
// cross a plane between two rows cost G_cr per unit area), `continuum` (docs/theory.md section 7's closed
// forms, their limit for a large horizon factor) or `dissipation` (lattice / rho: a running crack
// then dissipates G_cr per unit area; solver/damage_calibration.hpp).
enum class DamageCalibration { lattice, continuum, dissipation };

// Whether a bond whose work reached w_cr breaks while it is compressed (docs/theory.md section 7):
// `break` (default: the work criterion alone) or `hold` (it breaks only once stretched,
// |xi + U| > |xi|; compressive impacts then crush nothing).
enum class CompressedBonds { break_, hold };

// How the Drucker-Prager cone is fitted to Mohr-Coulomb (solver/plasticity/drucker_prager_cone.hpp).
enum class ConeMatch {
  triaxial_compression,  // outer cone: DP = MC on the compression meridian (default)
  plane_strain,          // DP = MC at the plane-strain limit state (for the given dilatancy)
};

// The scene's spelling of an enum value. One table per enum: the parser reads names with it, the
// resolved-scene writer writes them, and messages list the valid names from it.
template <class E>
struct EnumName {
  E value;
  const char* name;
};
inline constexpr std::array<EnumName<DamageCalibration>, 3> kDamageCalibrationNames{{
    {DamageCalibration::lattice, "lattice"},
    {DamageCalibration::continuum, "continuum"},
    {DamageCalibration::dissipation, "dissipation"},
}};
inline constexpr std::array<EnumName<CompressedBonds>, 2> kCompressedBondsNames{{
    {CompressedBonds::break_, "break"},
    {CompressedBonds::hold, "hold"},
}};
inline constexpr std::array<EnumName<ConeMatch>, 2> kConeMatchNames{{
    {ConeMatch::triaxial_compression, "triaxial-compression"},
    {ConeMatch::plane_strain, "plane-strain"},
}};
template <class E, std::size_t N>
constexpr const char* enum_name(const std::array<EnumName<E>, N>& table, E value) {
  for (const auto& entry : table) {
    if (entry.value == value) return entry.name;
  }
  return "?";
}
// Inline, so that libraries which only see the scene's types (solver/plasticity) need not link it.
inline const char* to_string(DamageCalibration calibration) { return enum_name(kDamageCalibrationNames, calibration); }
// How the pore fluid's flow is advanced when its stability limit is below the time step
// (docs/theory.md section 12): auto takes the RKL2 super step when it needs fewer flow evaluations
// than explicit substeps; explicit always subcycles.
enum class FlowIntegration { automatic, explicit_substeps };
inline constexpr std::array<EnumName<FlowIntegration>, 2> kFlowIntegrationNames{{
    {FlowIntegration::automatic, "auto"},
    {FlowIntegration::explicit_substeps, "explicit"},
}};
// Where the critical time step is estimated (docs/theory.md section 9): on patches around the
// stiffest points, the whole model's estimate when a patch cannot hold the highest mode; or always
// on the whole model.
enum class StepEstimate { patch, whole_model };
inline constexpr std::array<EnumName<StepEstimate>, 2> kStepEstimateNames{{
    {StepEstimate::patch, "patch"},
    {StepEstimate::whole_model, "whole_model"},
}};
inline const char* to_string(ConeMatch match) { return enum_name(kConeMatchNames, match); }
inline const char* to_string(CompressedBonds bonds) { return enum_name(kCompressedBondsNames, bonds); }
inline const char* to_string(FlowIntegration f) { return enum_name(kFlowIntegrationNames, f); }
inline const char* to_string(StepEstimate e) { return enum_name(kStepEstimateNames, e); }

struct DamageParameters {
  double critical_energy_release_rate = 0.0;  // G_cr [J/m^2]
  double no_fail_depth = 0.0;                 // [m] from kinematic and loaded boundaries
  DamageCalibration calibration = DamageCalibration::lattice;
  // Damage only inside this box (scene units of length, a 2-D box spans every z): bonds with an
  // end outside never break and cost no bond-work bookkeeping. Empty: the whole body.
  std::optional<Selector> region;
  CompressedBonds compressed_bonds = CompressedBonds::break_;
};

struct ViscoplasticParameters {
  std::string model = "drucker-prager-perzyna";
  double friction_angle = 0.0;     // [rad]
  double dilatancy_angle = 0.0;    // [rad]
  double cohesion = 0.0;           // c0 [Pa]
  double hardening = 0.0;          // h [Pa]
  double viscosity = 0.0;          // eta [Pa s]
  double residual_cohesion = 0.0;  // floor of c [Pa]
  ConeMatch cone_match = ConeMatch::triaxial_compression;
  // Viscoplastic flow only inside this box; outside the points stay elastic and skip the return
  // map. Empty: the whole body.
  std::optional<Selector> region;
};

// The pore fluid (docs/theory.md section 12), saturated: the fluid fills the pores. SI units.
// The unsaturated model's retention curve (docs/theory.md section 12, "Unsaturated (retention)"):
// van Genuchten's S_e = [1 + (s / p_e)^n]^(-m), m = 1 - 1/n, of the suction s = max(0, -p).
struct RetentionParameters {
  std::string model = "van_genuchten";  // the only one
  double air_entry_pressure = 0.0;      // p_e [Pa], > 0
  double n = 0.0;                       // > 1
  double residual_saturation = 0.0;     // S_res, in [0, 1)
};

struct PoreFluidParameters {
  double permeability = 0.0;      // intrinsic permeability k [m^2]
  double fluid_viscosity = 0.0;   // mu_f [Pa s]
  double fluid_density = 0.0;     // rho_f [kg/m^3]
  double biot_coefficient = 1.0;  // b, in (porosity, 1]
  double biot_modulus = 0.0;      // M [Pa]
  double initial_pressure = 0.0;  // p at t = 0 [Pa], compression positive (constant)
  // initial_pressure: hydrostatic: the level of the free surface (water table) along the up
  // direction -g [m]; p = rho_f |g| (free_surface - up . x) at t = 0. Empty: the constant pressure.
  std::optional<double> free_surface;
  // Unsaturated flow when given (read and written back; the solver refuses it until it is built).
  std::optional<RetentionParameters> retention;

  double mobility() const { return permeability / fluid_viscosity; }  // k' = k / mu_f [m^2/(Pa s)]
};

struct Material {
  std::string model = "cosserat-elastic";
  double density = 0.0;                                // skeleton partial density rho^s [kg/m^3]
  double solid_fraction = 1.0;                         // phi0^s
  double lambda = 0.0;                                 // [Pa]
  double mu = 0.0;                                     // [Pa]
  double mu_c = 0.0;                                   // Cosserat couple modulus [Pa]
  std::array<double, 3> couple_moduli{0.0, 0.0, 0.0};  // a1 a2 a3 [N]
  double length_scale = 0.0;                           // micro-polar length l [m]
  std::optional<DamageParameters> damage;
  std::optional<ViscoplasticParameters> viscoplasticity;
  std::optional<PoreFluidParameters> pore_fluid;

  double partial_density() const { return solid_fraction * density; }  // rho [kg/m^3]
  double porosity() const { return 1.0 - solid_fraction; }             // n0
  // Micro-inertia per unit volume I = 1/2 pi rho l^2 [kg/m] (docs/theory.md section 4).
  double micro_inertia() const;
  // Effective bending modulus B_w [N]: a3 in 2-D (docs/theory.md section 5); a2 in 3-D.
  double bending_modulus(int dimension) const;
};

struct Geometry {
  std::string file;             // absolute path
  double unit = 1.0;            // metres per geometry-file length unit
  double spacing = 0.0;         // dx [m]
  double horizon_factor = 0.0;  // delta / dx
  std::vector<Selector> precracks;
  double horizon() const { return spacing * horizon_factor; }
};

struct TimeSettings {
  double end = 0.0;            // [s]
  std::optional<double> step;  // [s]; empty = auto
  double safety = 0.8;         // dt = safety * critical when auto
};

struct OutputSettings {
  double interval = 0.0;       // snapshot interval [s] (0 = only first and last)
  double load_interval = 0.0;  // load/energy rows [s] (0 = every step)
  std::vector<std::string> fields{"displacement", "rotation", "damage"};
  double checkpoint_interval = 0.0;  // [s] (0 = none)
};

struct Numerics {
  double stabilization = 0.1;                 // G_s
  double damping = 0.0;                       // mass-proportional damping coefficient [1/s] (quasi-static runs)
  double energy_check_tolerance = 0.05;       // relative unexplained energy growth that stops a run
  std::int64_t energy_check_start_step = 50;  // the energy check skips the steps before this one
  // Damage thresholds (solver/bond_breakage.cpp and solver/point_stability.hpp say why these values):
  double detach_energy_rise = 0.5;       // a point whose stored energy rises by more than this share
                                         // when it loses bonds is detached
  double overload_factor = 1.5;          // above this multiple of its family's breaking energy, any
                                         // rise detaches the point
  double damaged_frequency_ratio = 3.5;  // allowed omega_max^2 / largest point block of a damaged lattice
  FlowIntegration flow_integration = FlowIntegration::automatic;  // pore fluid: solver/pore_fluid.cpp
  StepEstimate step_estimate = StepEstimate::patch;               // solver/critical_time_step.cpp
};

struct Scene {
  std::string path;  // absolute path of the scene file
  int format_version = 1;
  std::string name;
  int dimension = 2;
  double thickness = 1.0;  // [m], 2-D only
  Geometry geometry;
  Material material;
  EffectSet effects;
  std::array<double, 3> gravity{0.0, -9.81, 0.0};  // [m/s^2], used with the gravity effect
  std::vector<BoundaryCondition> boundary_conditions;
  TimeSettings time;
  OutputSettings output;
  Numerics numerics;
  std::vector<std::string> warnings;     // non-fatal findings (e.g. parameters of an effect that is off)
  std::map<std::string, int> key_lines;  // "boundary_conditions[1].boundary" -> line in the file

  // "scene.yaml:12: boundary_conditions[1].boundary" for messages about a key found invalid
  // by a later stage (e.g. a physical group the geometry does not have).
  std::string where(const std::string& key_path) const;
};

// Reads, overrides (`--set key.path=value`, applied before validation), fills defaults and
// validates a scene. Throws InputError("scene.yaml:LINE: key.path: problem (expected ...)").
Scene load_scene(const std::string& path, const std::vector<std::string>& overrides = {});

// Same, from text (tests); `path` is used in messages and to resolve relative paths.
Scene parse_scene(const std::string& text, const std::string& path, const std::vector<std::string>& overrides = {});

// The resolved scene as YAML (SI numbers, every default and derived value written out).
// `derived` adds solver-derived values (e.g. {"time_step_s", 2.5e-8}) under the key `derived`.
std::string resolved_scene_yaml(const Scene& scene, const std::vector<std::pair<std::string, double>>& derived = {});

}  // namespace mppm
