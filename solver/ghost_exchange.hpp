// The ghosts' source (docs/theory.md section 13): in a distributed run each process holds copies of
// the points of other processes within the bond reach of its own (ghosts, after the owned points in
// PointData), and brings them up to date from their owners when a pass needs them: the
// displacement and rotation before the force pass, the pass-1 tensors before pass 2. A single
// process has no ghosts and no exchange.
#pragma once
#include <vector>

namespace mppm::solver {

class GhostExchange {
 public:
  virtual ~GhostExchange() = default;
  // Copies the owners' values of a per-point field (`components` doubles per point) into the
  // ghosts' slots of `values`, on every process (a collective call).
  virtual void update_ghosts(std::vector<double>& values, int components) const = 0;
};

}  // namespace mppm::solver
