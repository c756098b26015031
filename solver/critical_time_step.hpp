// The stable time step of the explicit scheme (docs/theory.md section 9): the largest eigenvalue of
// M^-1 K of the actual discrete operator (stabilization included) by a Lanczos (Krylov-refined
// power) iteration, on the patches around the stiffest points when the highest mode lives there
// (model_patch.hpp), else on the whole model; plus the same for the translational block (w = 0)
// and the rotational block (u = 0) to name the mode that limits the step and the parameter that
// drives it.
#pragma once
#include <array>
#include <cstddef>
#include <optional>
#include <string>

#include "common/scene.hpp"
#include "solver/model.hpp"
#include "solver/model_patch.hpp"
#include "solver/point_stability.hpp"

namespace mppm::solver {

struct CriticalTimeStep {
  double step = 0.0;           // 2 / omega_max of the coupled operator [s]
  double translational = 0.0;  // of the translational block
  double rotational = 0.0;     // of the rotational block (0 = no rotation dofs)
  std::string limiting_mode;   // "translational" or "rotational"
  std::string driver;          // the parameter that drives the limiting mode, with its value
  int iterations = 0;          // operator applications of the coupled estimate
  int naming_iterations = 0;   // operator applications of the naming (0 when not named)
  // Where the mode was named: the own points of the patch (model_patch.hpp; 0: the whole model)
  // and its centre, the stiffest point [m].
  std::size_t naming_patch_points = 0;
  std::array<double, 3> naming_patch_centre{0.0, 0.0, 0.0};
  // A highest mode mixing both blocks named on each block's own patches: their own points
  // (translational, rotational; 0: not so named).
  std::array<std::size_t, 2> naming_block_patch_points{0, 0};
  // The step is a patch's estimate: the whole model's Lanczos run stopped short of it.
  bool step_from_patch = false;
  // Where the step was estimated: on the patch of this many own points (0: the whole model), and
  // otherwise why not on a patch (empty for a whole-model estimate nobody asked a patch of).
  std::size_t step_patch_points = 0;
  std::string whole_model_reason;
};

// The step's patch of 4 horizons around the stiffest point of all, with its coupled estimate: the
// naming tries that patch first, and takes it from here rather than cutting and estimating it
// again (the same bits: the same points, operator and start vector).
struct StepPatch {
  ModelPatch patch;
  std::array<double, 3> centre{0.0, 0.0, 0.0};
  double radius = 0.0;          // [m]
  double coupled_lambda = 0.0;  // omega_max^2 of the patch's coupled operator
};

// Each of these leaves the model's displacement and rotation as they were. Each is collective in a
// distributed run, and gives every process the same bits.
// The step and the limiting mode, both from the model (the mode named as name_limiting_mode does).
CriticalTimeStep critical_time_step(Model& model, StepEstimate where = StepEstimate::patch);
// The step only (translational, rotational, limiting_mode and driver unset), on the whole model.
CriticalTimeStep coupled_critical_time_step(Model& model);
// The step only, where `where` says: with StepEstimate::patch on the patches of 4 horizons around
// the stiffest point of all and the stiffest body point (`own`: this process's, stiffest_points),
// each checked against its patch of 3 horizons. When both patches hold their highest mode (the
// estimate rises by at most 1e-3 from 3 to 4 horizons), omega_max^2 is the larger 4-horizon
// estimate raised by that rise; else the step is the whole model's, with the reason in
// whole_model_reason. With `kept`, the patch around the stiffest point of all is left there for
// name_limiting_mode (empty when no such patch was estimated).
CriticalTimeStep estimate_critical_step(Model& model, StepEstimate where, const StiffestPoints& own,
                                        std::optional<StepPatch>* kept = nullptr);
// Names the mode of a coupled estimate from block estimates: translational, rotational,
// limiting_mode and driver. First on the patch around `centre` (the stiffest point, layers
// included: patch_centre of stiffest_points(...).any; docs/theory.md section 9),
// taken when the patch's limiting block reaches the critical step's coupled omega_max^2
// (`critical`'s estimate) within 2e-3 (the highest mode is that block's and lives there); if a
// patch's estimate is above that one by more than its convergence, the critical step becomes the
// patch's (a patch's Ritz value is a lower bound of omega_max^2). Where the patch holds a highest
// mode that mixes both blocks, each block on the patches around its own stiffest point
// (stiffest_parts; 4 horizons checked against 3, as the step's). Else on the whole model, at about 1.4 times the
// coupled estimate's cost with rotations (coarser estimates). `kept`: the step's patch, if it was
// kept (estimate_critical_step), which the first patch then is.
void name_limiting_mode(Model& model, CriticalTimeStep& critical, const PatchCentre& centre,
                        std::optional<StepPatch>* kept = nullptr);
// Whether the mode is tried on a patch first (then name_limiting_mode needs the stiffest point):
// with micro-rotations, on a model that can be cut into patches (model_patch.hpp). Collective.
bool names_mode_on_patch(const Model& model);
// Whether the patches need the stiffest points (stiffest_points): the step's with
// StepEstimate::patch, the naming's with micro-rotations, both only where the model can be cut
// into patches. Collective.
bool patches_need_stiffest_points(const Model& model, StepEstimate where);
// The same, finding the stiffest point itself.
void name_limiting_mode(Model& model, CriticalTimeStep& critical);
// How tightly the whole model's naming estimates converge: `naming`, the naming's own (relative
// change below 1e-2 over the last 3 of at least 10 iterations: the block steps long by up to about
// 5e-3),
// or `converged`, the step's (1e-8 over the last 5 of at least 20), for a reference value.
enum class NamingConvergence { naming, converged };
// On the whole model, without a patch.
void name_limiting_mode_on_whole_model(Model& model, CriticalTimeStep& critical,
                                       NamingConvergence convergence = NamingConvergence::naming);

// time.step: auto -> safety * critical; a given step above the critical one is refused with an
// InputError naming the limiting mode, its critical value and the parameter driving it. With the
// damage effect the bound is `damage_step` (Model::damage_critical_step) where it is lower.
double choose_time_step(const Scene& scene, const CriticalTimeStep& critical, double damage_step = 0.0);

}  // namespace mppm::solver
