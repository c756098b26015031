// The crack-arrival table of a damage run, RUN_DIR/crack_path.csv (common/crack_path.hpp,
// docs/stages.md): when each point reached the crack path. Damage only grows, so the crack path at
// time t is the points that arrived at or before t; the crack metrics (crack_metrics.hpp) take
// their frames from it at the times the path changed, instead of at the snapshots.
#pragma once
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "postprocess/crack_metrics.hpp"

namespace mppm::post {

struct CrackArrival {
  std::size_t point = 0;  // index in the points file
  double time = 0.0;      // [s]
};

// The table's rows in file order (time order), or nullopt when the run directory has none (a run
// without damage, or one written before the solver wrote the table). Throws InputError naming
// file:line for a malformed row, a point outside 0 .. point_count-1 or listed twice, or a time
// earlier than the row before. A last line without its newline cannot occur (the file is written
// atomically) and is an error too.
std::optional<std::vector<CrackArrival>> read_crack_path_table(const std::string& run_directory,
                                                               std::size_t point_count);

// The times of the tracker's frames: `first` (the first snapshot's time: the frame of the
// pre-crack), then the times in (first, last] at which the crack path changed, and `last` (the
// last snapshot's time) if the path did not change then. With `bin` > 0 the changes are taken in
// bins (first + (k-1) bin, first + k bin] and only the last change of each bin gets a frame (it
// holds every arrival of its bin), so that an event is dated at most `bin` late. With `hold` > 0
// (the time step) a change at t also gets a frame at t - hold, the last time the path was still
// the one before: a path that stayed put for a while is then seen at both ends of that while
// (the tip speed measures advances from the latest time a length was reached, as snapshots
// taken at that time would).
std::vector<double> crack_frame_times(const std::vector<CrackArrival>& arrivals, double first, double last,
                                      double bin = 0.0, double hold = 0.0);

// Feeds `tracker` the crack path at each of `times` (increasing): the points that arrived at or
// before that time.
void add_table_frames(CrackTracker& tracker, const std::vector<CrackArrival>& arrivals,
                      const std::vector<double>& times);

// Where the crack metrics' frames came from, for summary.json.
struct CrackFrameSource {
  std::string name;           // "crack_path table" | "snapshots"
  double resolution_s = 0.0;  // the most an event's time can lag the change that made it
  std::size_t frames = 0;
};

// Frames beyond this are too many: the changes are then taken in bins of (last - first) /
// (kMaxCrackTableFrames / 2) (crack_frame_times): each frame costs a shortest-path search over the
// crack path (about 0.7 ms for the 900 crack points of the crack-branching case).
inline constexpr std::size_t kMaxCrackTableFrames = 4000;

// The tracker's frames from the table between the first and the last snapshot (first, last): at
// every time the crack path changed and the step before it (`time_step`, the run's), which dates
// events to the time step, or in bins when that would be more than kMaxCrackTableFrames frames.
CrackFrameSource add_crack_path_frames(CrackTracker& tracker, const std::vector<CrackArrival>& arrivals, double first,
                                       double last, double time_step);

}  // namespace mppm::post
