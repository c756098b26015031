// The test hooks of mppm-solve: their options parsed, checked against the run, and applied.
#include "solver/test_hooks.hpp"

#include <algorithm>
#include <cmath>
#include <exception>
#include <limits>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "common/input_error.hpp"
#include "common/units.hpp"
#include "solver/log_number.hpp"

namespace mppm::solver {

namespace {

// The value of a test hook (--inject-nan, --inject-kick) cut at its colons.
std::vector<std::string> hook_parts(const std::string& value) {
  std::vector<std::string> parts;
  std::size_t start = 0;
  for (std::size_t at; (at = value.find(':', start)) != std::string::npos; start = at + 1)
    parts.push_back(value.substr(start, at - start));
  parts.push_back(value.substr(start));
  return parts;
}

// A 1-based ("3") or 0-based ("17") non-negative integer of a test hook; `form` says what the
// hook expects, for the message.
std::int64_t hook_integer(const std::string& hook, const std::string& value, const std::string& part,
                          const std::string& what, const std::string& form) {
  std::size_t used = 0;
  long long v = -1;
  try {
    v = std::stoll(part, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != part.size() || part.empty() || v < 0)
    throw InputError("" + hook + " " + value + ": " + what + " '" + part + "' is not a non-negative integer" + form);
  return v;
}

// The step of a test hook, from 1.
std::int64_t hook_step(const std::string& hook, const std::string& value, const std::string& part,
                       const std::string& form) {
  const std::int64_t step = hook_integer(hook, value, part, "STEP", form);
  if (step < 1) throw InputError("" + hook + " " + value + ": STEP counts from 1 (the first step)");
  return step;
}

// The fields --inject-nan can write: name, array and whether it holds rotations (R per point)
// rather than vectors (D per point). The one list the name, the parser and the checks use.
struct NanField {
  NanInjection::Field field;
  const char* name;
  std::vector<double> PointData::*array;
  bool rotational;
};
constexpr NanField kNanFields[] = {
    {NanInjection::Field::displacement, "displacement", &PointData::displacement, false},
    {NanInjection::Field::velocity, "velocity", &PointData::velocity, false},
    {NanInjection::Field::rotation, "rotation", &PointData::rotation, true},
    {NanInjection::Field::rotation_rate, "rotation_rate", &PointData::spin, true},
    {NanInjection::Field::force, "force", &PointData::force, false},
};

const NanField& nan_field(NanInjection::Field f) {
  for (const NanField& entry : kNanFields)
    if (entry.field == f) return entry;
  throw std::logic_error("NanInjection: a field missing from kNanFields");
}

// Components per point of a field in this run (0: a rotation without micropolar).
int nan_field_components(const PointData& p, NanInjection::Field f) {
  return nan_field(f).rotational ? p.rotation_components : p.dimension;
}

void write_nan(PointData& p, std::size_t i, const NanInjection& k) {
  const auto width = static_cast<std::size_t>(nan_field_components(p, k.field));
  (p.*nan_field(k.field).array)[i * width + static_cast<std::size_t>(k.component)] =
      std::numeric_limits<double>::quiet_NaN();
}

}  // namespace

const char* NanInjection::name(Field f) { return nan_field(f).name; }

NanInjection parse_nan_injection(const std::string& value) {
  const std::vector<std::string> parts = hook_parts(value);
  const std::string hook = "--inject-nan";
  const std::string form = " (expected STEP:POINT[:FIELD[:COMPONENT]], e.g. 200:17:velocity)";
  if (parts.size() < 2 || parts.size() > 4) throw InputError("" + hook + " " + value + ":" + form);
  NanInjection k;
  k.step = hook_step(hook, value, parts[0], form);
  k.point = static_cast<std::size_t>(hook_integer(hook, value, parts[1], "POINT", form));
  if (parts.size() > 2) {
    const NanField* known = nullptr;
    std::string names;
    for (const NanField& entry : kNanFields) {
      if (parts[2] == entry.name) known = &entry;
      names += (names.empty() ? "" : ", ") + std::string(entry.name);
    }
    if (!known)
      throw InputError("--inject-nan " + value + ": unknown FIELD '" + parts[2] + "' (expected one of " + names + ")");
    k.field = known->field;
  }
  if (parts.size() > 3) k.component = static_cast<int>(hook_integer(hook, value, parts[3], "COMPONENT", form));
  return k;
}

VelocityKick parse_velocity_kick(const std::string& value) {
  const std::vector<std::string> parts = hook_parts(value);
  const std::string hook = "--inject-kick";
  const std::string form = " (expected STEP:POINT:COMPONENT:VELOCITY, e.g. 60:17:0:50)";
  if (parts.size() != 4) throw InputError("" + hook + " " + value + ":" + form);
  VelocityKick k;
  k.step = hook_step(hook, value, parts[0], form);
  k.point = static_cast<std::size_t>(hook_integer(hook, value, parts[1], "POINT", form));
  k.component = static_cast<int>(hook_integer(hook, value, parts[2], "COMPONENT", form));
  try {
    k.velocity = parse_quantity_as(parts[3], dim::velocity);
  } catch (const std::invalid_argument& e) {
    throw InputError("--inject-kick " + value + ": VELOCITY: " + e.what() + form);
  }
  if (!std::isfinite(k.velocity)) throw InputError("--inject-kick " + value + ": VELOCITY must be finite" + form);
  return k;
}

int parse_checkpoint_write_failure(const std::string& value) {
  try {
    std::size_t used = 0;
    const int k = std::stoi(value, &used);
    if (used != value.size() || k < 1) throw std::invalid_argument(value);
    return k;
  } catch (const std::exception&) {
    throw InputError("--fail-checkpoint-write " + value + ": expected K >= 1 (the K-th checkpoint write fails)");
  }
}

void TestHooks::check_against_model(const Model& model, std::uint64_t points, const std::string& points_file) const {
  if (const auto& k = inject_nan) {
    const int components = nan_field_components(model.points, k->field);
    if (k->point >= points)
      throw InputError("--inject-nan: POINT " + std::to_string(k->point) + " is not a point of " + points_file +
                       " (expected 0 to " + std::to_string(points - 1) + ")");
    if (components == 0)
      throw InputError(std::string("--inject-nan: FIELD ") + NanInjection::name(k->field) +
                       " needs the micropolar effect (this run has no micro-rotation)");
    if (k->component >= components)
      throw InputError("--inject-nan: COMPONENT " + std::to_string(k->component) + " of " +
                       NanInjection::name(k->field) + " (expected 0 to " + std::to_string(components - 1) + ")");
  }
  if (const auto& k = inject_kick) {
    if (k->point >= points)
      throw InputError("--inject-kick: POINT " + std::to_string(k->point) + " is not a point of " + points_file +
                       " (expected 0 to " + std::to_string(points - 1) + ")");
    if (k->component >= model.dimension())
      throw InputError("--inject-kick: COMPONENT " + std::to_string(k->component) + " of the velocity (expected 0 to " +
                       std::to_string(model.dimension() - 1) + ")");
  }
}

void TestHooks::check_against_steps(std::int64_t steps) const {
  auto beyond = [&](const char* hook, std::int64_t step) {
    return InputError(std::string(hook) + ": STEP " + std::to_string(step) + " is beyond the run's " +
                      std::to_string(steps) + " steps (expected 1 to " + std::to_string(steps) + ")");
  };
  if (inject_nan && inject_nan->step > steps) throw beyond("--inject-nan", inject_nan->step);
  if (inject_kick && inject_kick->step > steps) throw beyond("--inject-kick", inject_kick->step);
}

void TestHooks::refuse_with_restart() const {
  if (inject_nan) throw InputError("--inject-nan cannot be combined with --restart");
  if (inject_kick) throw InputError("--inject-kick cannot be combined with --restart");
}

std::vector<std::string> TestHooks::armed() const {
  std::vector<std::string> lines;
  if (const auto& k = inject_nan)
    lines.push_back("test hook (--inject-nan): a NaN will be written into " +
                    std::string(NanInjection::name(k->field)) + " component " + std::to_string(k->component) +
                    " of point " + std::to_string(k->point) + " in step " + std::to_string(k->step));
  if (const auto& k = inject_kick)
    lines.push_back("test hook (--inject-kick): " + log_number(k->velocity) +
                    " m/s will be added to velocity component " + std::to_string(k->component) + " of point " +
                    std::to_string(k->point) + " in step " + std::to_string(k->step) +
                    " (kinetic energy that nothing accounts for)");
  return lines;
}

void TestHooks::after_forces(PointData& points, std::int64_t step) const {
  if (inject_nan && inject_nan->step == step)
    if (const auto i = owned_index(points, inject_nan->point)) write_nan(points, *i, *inject_nan);
  if (inject_kick && inject_kick->step == step)
    if (const auto i = owned_index(points, inject_kick->point))
      points.velocity[*i * static_cast<std::size_t>(points.dimension) +
                      static_cast<std::size_t>(inject_kick->component)] += inject_kick->velocity;
}

}  // namespace mppm::solver
