// The plane of the 3-D clip pictures (`mppm-postprocess --clip x=50mm`): an axis and a position
// on it, in the reference configuration. The clip pictures show the part of the body behind
// the plane, its cut face towards the camera (postprocess/README.md, "Figures").
#pragma once
#include <array>
#include <optional>
#include <string>

#include "common/snapshot_file.hpp"

namespace mppm::post {

struct ClipPlane {
  int axis = 0;           // 0, 1, 2: the plane x, y or z = position
  double position = 0.0;  // [m]
};

// "x=50mm", "y = 0.01" (plain numbers are metres). Throws InputError naming --clip and saying
// what was expected.
ClipPlane parse_clip_plane(const std::string& text);

// The extent of the body points (region 0; every point when the file has no region) of the
// reference snapshot: {min x, max x, min y, max y, min z, max z} [m].
std::array<double, 6> body_bounds(const Snapshot& reference);

// The requested plane, checked against the body, or by default the mid-plane across the body's
// largest extent. Throws InputError when a plane is requested for a 2-D run or lies outside
// the body.
ClipPlane resolve_clip_plane(const std::optional<ClipPlane>& requested, const Snapshot& reference, int dimension);

// "x", "y" or "z".
std::string axis_name(int axis);

// "50 mm", "1.2 m", "20 um": a length with a readable unit.
std::string format_length(double metres);

}  // namespace mppm::post
