// The ghosts' source (docs/theory.md section 13): in a distributed run each process holds copies of
// the points of other processes within the bond reach of its own (ghosts, after the owned points in
// PointData), and brings them up to date from their owners when a pass needs them: the
// displacement and rotation before the force pass, the pass-1 tensors before pass 2. A single
// process has no ghosts and no exchange.
#pragma once
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace mppm::solver {

// A value about one local point: sent about a ghost, received about an owned point.
struct PointNote {
  std::size_t point = 0;  // local index
  std::int64_t value = 0;
};

class GhostExchange {
 public:
  virtual ~GhostExchange() = default;
  // Copies the owners' values of a per-point field (`components` doubles per point) into the
  // ghosts' slots of `values`, on every process (a collective call).
  virtual void update_ghosts(std::vector<double>& values, int components) const = 0;
  // The reverse direction: sends each note about a ghost to that ghost's owner, and returns the
  // notes the other processes sent about this one's owned points (by sending process, then in
  // its order). A collective call (damage: a bond broken at one end, to be broken at the other).
  virtual std::vector<PointNote> notify_owners(std::span<const PointNote> about_ghosts) const = 0;
  // update_ghosts in two halves, so that work that reads no ghost runs while the values travel:
  // begin_update sends this process's values of a field (several fields may be begun, in the same
  // order on every process); finish_updates waits for the ghosts' values of every begun field and
  // puts them in place. A begun field's values must not change before finish_updates.
  virtual void begin_update(std::vector<double>& values, int components) const = 0;
  virtual void finish_updates() const = 0;
  // Lets the begun fields' messages move on (called between blocks of work while they travel).
  virtual void advance_transfers() const = 0;
};

}  // namespace mppm::solver
