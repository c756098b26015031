// The plane of the 3-D clip pictures (see clip_plane.hpp).
#include "postprocess/clip_plane.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "common/comma_list.hpp"
#include "common/input_error.hpp"
#include "common/units.hpp"

namespace mppm::post {

namespace {

constexpr const char* kClipForm = "expected AXIS=LENGTH with AXIS x, y or z, e.g. --clip x=50mm";

[[noreturn]] void refuse(const std::string& text, const std::string& problem) {
  throw InputError("--clip '" + text + "': " + (problem.empty() ? "" : problem + "; ") + kClipForm);
}

}  // namespace

std::string axis_name(int axis) { return std::string(1, static_cast<char>('x' + axis)); }

std::string format_length(double metres) {
  char buffer[48];
  const double size = std::fabs(metres);
  if (size != 0.0 && size < 1e-3)
    std::snprintf(buffer, sizeof buffer, "%.4g um", metres * 1e6);
  else if (size != 0.0 && size < 1.0)
    std::snprintf(buffer, sizeof buffer, "%.4g mm", metres * 1e3);
  else
    std::snprintf(buffer, sizeof buffer, "%.4g m", metres);
  return buffer;
}

ClipPlane parse_clip_plane(const std::string& text) {
  const std::size_t equals = text.find('=');
  if (equals == std::string::npos) refuse(text, "");
  const std::string axis = trim_blanks(text.substr(0, equals));
  const std::string length = trim_blanks(text.substr(equals + 1));
  if (axis.size() != 1 || axis[0] < 'x' || axis[0] > 'z') refuse(text, "the axis '" + axis + "' is not x, y or z");
  ClipPlane plane;
  plane.axis = axis[0] - 'x';
  try {
    plane.position = parse_quantity_as(length, dim::length);
  } catch (const std::exception& e) {
    refuse(text, e.what());
  }
  if (!std::isfinite(plane.position)) refuse(text, "the position is not a finite length");
  return plane;
}

std::array<double, 6> body_bounds(const Snapshot& reference) {
  const SnapshotField* position = reference.find("position");
  if (!position || position->components != 3) throw InputError("reference snapshot: no 3-component 'position'");
  const SnapshotField* region = reference.find("region");
  constexpr double kHuge = std::numeric_limits<double>::max();
  std::array<double, 6> bounds{kHuge, -kHuge, kHuge, -kHuge, kHuge, -kHuge};
  for (std::uint64_t i = 0; i < reference.point_count; ++i) {
    if (region && region->data[i] != 0.0) continue;  // boundary layers lie outside the body
    for (int c = 0; c < 3; ++c) {
      bounds[2 * c] = std::min(bounds[2 * c], position->data[3 * i + c]);
      bounds[2 * c + 1] = std::max(bounds[2 * c + 1], position->data[3 * i + c]);
    }
  }
  return bounds;
}

ClipPlane resolve_clip_plane(const std::optional<ClipPlane>& requested, const Snapshot& reference, int dimension) {
  if (dimension != 3) {
    if (requested) throw InputError("--clip cuts 3-D bodies; this run is " + std::to_string(dimension) + "-D");
    return {};
  }
  const std::array<double, 6> bounds = body_bounds(reference);
  if (!requested) {  // the mid-plane across the largest extent (the first such axis on a tie)
    ClipPlane plane;
    for (int c = 1; c < 3; ++c)
      if (bounds[2 * c + 1] - bounds[2 * c] > bounds[2 * plane.axis + 1] - bounds[2 * plane.axis]) plane.axis = c;
    plane.position = 0.5 * (bounds[2 * plane.axis] + bounds[2 * plane.axis + 1]);
    return plane;
  }
  const int c = requested->axis;
  if (requested->position < bounds[2 * c] || requested->position > bounds[2 * c + 1])
    throw InputError("--clip " + axis_name(c) + "=" + format_length(requested->position) +
                     ": the plane misses the body, whose points span " + axis_name(c) + " = " +
                     format_length(bounds[2 * c]) + " to " + format_length(bounds[2 * c + 1]));
  return *requested;
}

}  // namespace mppm::post
