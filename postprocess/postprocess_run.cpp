// The postprocessing driver: checks the run directory, streams the snapshots one at a time
// (ParaView frames, crack tracking), then writes the load curve, the summary and view.py (the
// ParaView state, paraview_state.hpp), and has the pictures made (pictures.hpp).
// Outputs are committed atomically; results.pvd is rewritten after every frame so that an
// interrupted postprocess (or a truncated snapshot) leaves a readable partial series.
#include "postprocess/postprocess_run.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <optional>
#include <set>

#include "common/atomic_file.hpp"
#include "common/input_error.hpp"
#include "common/output_directory.hpp"
#include "common/progress.hpp"
#include "common/run_directory.hpp"
#include "common/snapshot_file.hpp"
#include "common/units.hpp"
#include "postprocess/boundary_layer_mask.hpp"
#include "postprocess/clip_plane.hpp"
#include "postprocess/crack_angle.hpp"
#include "postprocess/crack_area_metrics.hpp"
#include "postprocess/crack_metrics.hpp"
#include "postprocess/crack_path_table.hpp"
#include "postprocess/derived_fields.hpp"
#include "postprocess/load_curve.hpp"
#include "postprocess/mid_thickness_layer.hpp"
#include "postprocess/paraview_state.hpp"
#include "postprocess/pictures.hpp"
#include "postprocess/pore_pressure_metrics.hpp"
#include "postprocess/run_directory_reader.hpp"
#include "postprocess/shear_band_metrics.hpp"
#include "postprocess/yaml_to_json.hpp"

namespace mppm::post {
namespace fs = std::filesystem;

namespace {

constexpr const char* kVtuDirectory = "results";

void write_text(const std::string& path, const std::string& text) {
  write_file_atomically(path, [&](std::ostream& out) { out << text; });
}

std::string frame_file_name(std::int64_t step) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "results_%06lld.vtu", static_cast<long long>(step));
  return buffer;
}

// The arrays of one frame as written: 2-component vectors of a 2-D run padded to 3 (ParaView
// warps and glyphs only by 3-vectors), plus the derived invariants.
struct FrameArrays {
  std::vector<std::vector<double>> storage;
  std::vector<PointArray> arrays;
};

FrameArrays frame_arrays(const Snapshot& snapshot, std::vector<std::string>& notes) {
  FrameArrays frame;
  frame.storage.reserve(snapshot.fields.size() + 4);  // keep pointers stable
  const std::size_t n = snapshot.point_count;
  for (const auto& field : snapshot.fields) {
    if (snapshot.dimension == 2 && field.components == 2) {
      std::vector<double> padded(3 * n);
      for (std::size_t i = 0; i < n; ++i) {
        padded[3 * i] = field.data[2 * i];
        padded[3 * i + 1] = field.data[2 * i + 1];
        padded[3 * i + 2] = 0.0;
      }
      frame.storage.push_back(std::move(padded));
      frame.arrays.push_back({field.name, 3, frame.storage.back().data()});
    } else {
      frame.arrays.push_back({field.name, field.components, field.data.data()});
    }
  }
  if (const SnapshotField* stress = snapshot.find("stress")) {
    const std::vector<double>* tensor = nullptr;
    std::vector<double> embedded;
    if (stress->components == 9) {
      tensor = &stress->data;
    } else if (stress->components == 4 && snapshot.dimension == 2) {
      // The in-plane block only (xx, xy, yx, yy): embedded with sigma_zz = 0.
      embedded.assign(9 * n, 0.0);
      for (std::size_t i = 0; i < n; ++i) {
        embedded[9 * i] = stress->data[4 * i];
        embedded[9 * i + 1] = stress->data[4 * i + 1];
        embedded[9 * i + 3] = stress->data[4 * i + 2];
        embedded[9 * i + 4] = stress->data[4 * i + 3];
      }
      tensor = &embedded;
      const std::string note =
          "stress has the 4 in-plane components only: von_mises_stress and mean_stress "
          "are those of the in-plane state (sigma_zz taken as 0)";
      if (std::find(notes.begin(), notes.end(), note) == notes.end()) notes.push_back(note);
    } else {
      const std::string note = "stress has " + std::to_string(stress->components) +
                               " components (expected 9, or 4 in 2-D): no stress invariants";
      if (std::find(notes.begin(), notes.end(), note) == notes.end()) notes.push_back(note);
    }
    if (tensor) {
      frame.storage.push_back(von_mises_stress(*tensor));
      frame.arrays.push_back({"von_mises_stress", 1, frame.storage.back().data()});
      frame.storage.push_back(mean_stress(*tensor));
      frame.arrays.push_back({"mean_stress", 1, frame.storage.back().data()});
    }
  }
  if (const SnapshotField* couple = snapshot.find("couple_stress")) {
    frame.storage.push_back(magnitude(couple->data, couple->components));
    frame.arrays.push_back({"couple_stress_magnitude", 1, frame.storage.back().data()});
  }
  return frame;
}

std::vector<int> integer_field(const Snapshot& reference, const char* name) {
  const SnapshotField* field = reference.find(name);
  std::vector<int> values(reference.point_count, 0);
  if (field)
    for (std::size_t i = 0; i < values.size(); ++i) values[i] = static_cast<int>(std::lround(field->data[i]));
  return values;
}

// `layout`: the fields (name, components) of the first snapshot, which every frame must hold.
void check_snapshot(const Snapshot& snapshot, const RunDirectory& run, const SnapshotEntry& entry,
                    const std::vector<std::pair<std::string, int>>& layout) {
  if (static_cast<std::int64_t>(snapshot.point_count) != run.info.points)
    throw InputError(entry.path + ": holds " + std::to_string(snapshot.point_count) + " points, the run has " +
                     std::to_string(run.info.points));
  if (snapshot.dimension != run.info.dimension)
    throw InputError(entry.path + ": dimension " + std::to_string(snapshot.dimension) + " differs from the run's " +
                     std::to_string(run.info.dimension));
  if (std::fabs(snapshot.time - entry.time) > 1e-9 * std::max(1.0, std::fabs(entry.time)) + 1e-15)
    throw InputError(entry.path + ": time " + std::to_string(snapshot.time) + " s differs from run_info.json (" +
                     std::to_string(entry.time) + " s)");
  for (const auto& [name, components] : layout) {
    const SnapshotField* same = snapshot.find(name);
    if (!same) throw InputError(entry.path + ": field '" + name + "' is missing (the first snapshot has it)");
    if (same->components != components)
      throw InputError(entry.path + ": field '" + name + "' has " + std::to_string(same->components) + " components, " +
                       std::to_string(components) + " in the first snapshot");
  }
}

std::string format_time(double seconds) {
  char buffer[48];
  if (seconds != 0.0 && std::fabs(seconds) < 1e-3)
    std::snprintf(buffer, sizeof buffer, "t = %.4g us", seconds * 1e6);
  else if (seconds != 0.0 && std::fabs(seconds) < 1.0)
    std::snprintf(buffer, sizeof buffer, "t = %.4g ms", seconds * 1e3);
  else
    std::snprintf(buffer, sizeof buffer, "t = %.4g s", seconds);
  return buffer;
}

// Snapshot indices for the figures.
std::vector<std::size_t> figure_frames(const std::vector<std::string>& times,
                                       const std::vector<SnapshotEntry>& snapshots) {
  std::vector<std::size_t> frames;
  if (times.empty()) return {snapshots.size() - 1};
  if (times.size() == 1 && times[0] == "all") {
    for (std::size_t k = 0; k < snapshots.size(); ++k) frames.push_back(k);
    return frames;
  }
  // Half the largest gap between snapshots: a requested time farther than that from every
  // snapshot is outside the series.
  double gap = 0.0;
  for (std::size_t k = 1; k < snapshots.size(); ++k) gap = std::max(gap, snapshots[k].time - snapshots[k - 1].time);
  for (const auto& text : times) {
    double t = 0.0;
    try {
      t = parse_quantity_as(text, dim::time);
    } catch (const std::exception& e) {
      throw InputError("--times: '" + text + "': " + e.what() + " (expected times such as '20 us', or 'all')");
    }
    std::size_t best = 0;
    for (std::size_t k = 1; k < snapshots.size(); ++k)
      if (std::fabs(snapshots[k].time - t) < std::fabs(snapshots[best].time - t)) best = k;
    if (std::fabs(snapshots[best].time - t) > 0.5 * gap + 1e-12 * std::fabs(t))
      throw InputError("--times: no snapshot near " + text + " (the run has snapshots from " +
                       std::to_string(snapshots.front().time) + " s to " + std::to_string(snapshots.back().time) +
                       " s)");
    if (std::find(frames.begin(), frames.end(), best) == frames.end()) frames.push_back(best);
  }
  std::sort(frames.begin(), frames.end());
  return frames;
}

// The first snapshot, read before anything is written: the options that name fields are
// checked against it, and every later frame must have its fields.
struct FirstSnapshot {
  Snapshot snapshot;
  std::vector<std::pair<std::string, int>> layout;  // (name, components) of its fields
  std::vector<std::string> array_names;             // the arrays of a frame, derived ones included
};

FirstSnapshot read_first_snapshot(const RunDirectory& run) {
  FirstSnapshot first;
  first.snapshot = read_snapshot(run.info.snapshots.front().path);
  check_snapshot(first.snapshot, run, run.info.snapshots.front(), {});
  for (const auto& field : first.snapshot.fields) first.layout.emplace_back(field.name, field.components);
  std::vector<std::string> ignored;
  for (const auto& a : frame_arrays(first.snapshot, ignored).arrays) first.array_names.push_back(a.name);
  return first;
}

// --fields, each checked against the arrays of a frame; by default those of damage,
// plastic_shear_strain and rotation the run has, else displacement.
std::vector<std::string> choose_figure_fields(const std::vector<std::string>& requested, const FirstSnapshot& first) {
  std::vector<std::string> figure_fields = requested;
  if (figure_fields.empty())
    for (const char* name : {"damage", "plastic_shear_strain", "pore_pressure", "rotation"})
      if (first.snapshot.find(name)) figure_fields.emplace_back(name);
  if (figure_fields.empty() && first.snapshot.find("displacement")) figure_fields.emplace_back("displacement");
  const std::vector<std::string>& array_names = first.array_names;
  for (const auto& name : figure_fields)
    if (std::find(array_names.begin(), array_names.end(), name) == array_names.end()) {
      std::string available;
      for (const auto& a : array_names) available += (available.empty() ? "" : ", ") + a;
      throw InputError("--fields: the run has no field '" + name + "' (available: " + available + ")");
    }
  return figure_fields;
}

// --movie FIELD, checked against the arrays of a frame as --fields is.
void check_movie_field(const std::string& field, const FirstSnapshot& first) {
  if (field.empty()) return;
  const std::vector<std::string>& names = first.array_names;
  if (std::find(names.begin(), names.end(), field) != names.end()) return;
  std::string available;
  for (const auto& a : names) available += (available.empty() ? "" : ", ") + a;
  throw InputError("--movie: the run has no field '" + field + "' (available: " + available + ")");
}

// Creates (or with --force replaces) the post directory and its results/ folder; the earlier
// post directory is deleted beside the stage (keep the returned object while it runs).
EarlierOutputRemoval prepare_post_directory(const PostprocessOptions& options) {
  const fs::path post(options.output_directory);
  std::error_code ec;
  // --force replaces the whole directory: it must not hold the run being read.
  const auto directory_path = [&ec](const fs::path& p) {  // "run/" and "run" alike
    fs::path canonical = fs::weakly_canonical(p, ec);
    return canonical.has_filename() || !canonical.has_parent_path() ? canonical : canonical.parent_path();
  };
  const fs::path run_path = directory_path(options.run_directory);
  const fs::path post_path = directory_path(post);
  if (!ec &&
      std::mismatch(post_path.begin(), post_path.end(), run_path.begin(), run_path.end()).first == post_path.end())
    throw InputError(options.output_directory + ": the post directory must not be (or contain) the run directory " +
                     options.run_directory);
  EarlierOutputRemoval earlier = prepare_output_directory(
      options.output_directory, options.force,
      {"post directory", "-o POST_DIR", {"results.pvd", "summary.json", "load_curve.csv", kVtuDirectory}});
  fs::create_directories(post / kVtuDirectory, ec);
  if (ec) throw InputError(options.output_directory + ": cannot create the output directory (" + ec.message() + ")");
  return earlier;
}

// Reference positions and tags of the points, for the metrics.
struct PointGeometry {
  std::vector<double> x, y, z;
  std::vector<int> region, boundary_id;
  std::vector<char> body;  // region 0
};

PointGeometry point_geometry(const Snapshot& reference) {
  const std::size_t n = reference.point_count;
  const SnapshotField* position = reference.find("position");
  PointGeometry points;
  points.x.resize(n);
  points.y.resize(n);
  points.z.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    points.x[i] = position->data[3 * i];
    points.y[i] = position->data[3 * i + 1];
    points.z[i] = position->data[3 * i + 2];
  }
  points.region = integer_field(reference, "region");
  points.boundary_id = integer_field(reference, "boundary_id");
  points.body.resize(n);
  for (std::size_t i = 0; i < n; ++i) points.body[i] = points.region[i] == 0;
  return points;
}

// Crack tracking on the body points, if `track` (a 2-D run with a damage field or a crack-arrival table).
std::optional<CrackTracker> crack_tracker(const RunDirectory& run, const PointGeometry& points, bool track) {
  std::optional<CrackTracker> crack;
  if (track) {
    CrackSettings settings;
    settings.spacing = run.spacing;
    settings.horizon = run.horizon;
    crack.emplace(points.x, points.y, points.z, points.body, settings);
  }
  return crack;
}

// The snapshot of --crack-angle-time: the last at or before it (to the tolerance of snapshot
// times, check_snapshot), if any.
std::optional<std::size_t> snapshot_at_or_before(const std::vector<SnapshotEntry>& snapshots, double time) {
  std::optional<std::size_t> chosen;
  for (std::size_t k = 0; k < snapshots.size(); ++k)
    if (snapshots[k].time <= time + 1e-9 * std::max(std::fabs(time), std::fabs(snapshots[k].time))) chosen = k;
  return chosen;
}

// A 3-D run's crack angles are measured on its mid-thickness layer (mid_thickness_layer.hpp),
// with a crack tracker of its own for the layer's free surface (the tips). On the heap: the
// angle tracker keeps references to these arrays.
struct AngleLayer {
  MidThicknessLayer layer;
  CrackTracker tracker;
};

// In 3-D the damage beside a planar crack reaches the crack threshold 0.35 only from a horizon
// factor of about 3: 0.31 at 2.05 (10 of a point's 32 bonds cross a plane beside it), 0.39 at
// 3.05 (postprocess/README.md "3-D crack metrics"); below, the layer's crack path would miss the
// crack.
constexpr double kLayerAngleLeastHorizonFactor = 3.0;

// The crack angles, measured as the snapshots stream (crack_angle.hpp): on every snapshot until
// each tip's crack has reached the ring's outer radius, or with --crack-angle-time on the one
// snapshot it picks.
struct CrackAngleStream {
  std::unique_ptr<AngleLayer> layer;  // 3-D runs
  std::unique_ptr<CrackAngleTracker> tracker;
  std::optional<std::size_t> only_snapshot;
  std::vector<std::string> notes;

  void add(std::size_t k, const Snapshot& snapshot) {
    if (!tracker || (only_snapshot && k != *only_snapshot) || tracker->settled()) return;
    tracker->add_frame(snapshot.time, snapshot.find("damage")->data);
  }
};

// The crack angles' layer of a 3-D damage run, or a note why there is none.
std::unique_ptr<AngleLayer> angle_layer(const RunDirectory& run, const PointGeometry& points,
                                        std::vector<std::string>& notes) {
  if (run.horizon < kLayerAngleLeastHorizonFactor * run.spacing * (1 - 1e-9)) {
    notes.push_back(
        "crack angle: not measured: on a 3-D run's mid-thickness layer it needs a horizon factor of at "
        "least 3 (this run's horizon is " +
        format_length(run.horizon) + " at dx = " + format_length(run.spacing) +
        "), below which the damage beside a planar crack stays under the crack threshold 0.35");
    return nullptr;
  }
  MidThicknessLayer layer = mid_thickness_layer(points.z, points.body, run.spacing);
  CrackSettings settings;
  settings.spacing = run.spacing;
  settings.horizon = run.horizon;
  CrackTracker tracker(points.x, points.y, layer.flat_z, layer.include, settings);
  return std::make_unique<AngleLayer>(AngleLayer{std::move(layer), std::move(tracker)});
}

// The tips and rings of the crack angles, from the first snapshot, with the crack tracker's
// threshold and free-surface points: in 2-D on the body, with crack tracking; in 3-D on the
// mid-thickness layer.
CrackAngleStream crack_angle_stream(const RunDirectory& run, const PointGeometry& points, const FirstSnapshot& first,
                                    const std::optional<CrackTracker>& crack, CrackAngleSettings settings) {
  CrackAngleStream stream;
  // The angles need the damage fields (a run with the crack table alone has none in its snapshots).
  const auto* damage = first.snapshot.find("damage");
  if (!damage || (run.info.dimension == 2 && !crack)) return stream;
  if (run.info.dimension == 3) {
    stream.layer = angle_layer(run, points, stream.notes);
    if (!stream.layer) return stream;
  }
  const CrackTracker& tracker = stream.layer ? stream.layer->tracker : *crack;
  const std::vector<double>& z = stream.layer ? stream.layer->layer.flat_z : points.z;
  const std::vector<char>& include = stream.layer ? stream.layer->layer.include : points.body;
  settings.spacing = run.spacing;
  settings.horizon = run.horizon;
  settings.damage_threshold = tracker.damage_threshold();
  stream.tracker = std::make_unique<CrackAngleTracker>(
      CrackAngleLattice{points.x, points.y, z, include, tracker.near_boundary()}, damage->data, settings);
  if (settings.measure_time) stream.only_snapshot = snapshot_at_or_before(run.info.snapshots, *settings.measure_time);
  return stream;
}

// The frames written, and the last plastic shear strain field (for the shear-band metrics).
struct SeriesResult {
  std::vector<PvdEntry> entries;
  std::vector<double> last_plastic_shear;
  double last_plastic_time = 0.0;
  std::optional<PorePressureTracker> pore_pressure;  // when the snapshots have pore_pressure
};

// Streams the snapshots one at a time into results/*.vtu and results.pvd, feeding the crack
// tracker, the crack angles and the crack area (3-D). The first snapshot is taken over from
// `first` (and its memory released).
SeriesResult write_series(const RunDirectory& run, FirstSnapshot& first, const PostprocessOptions& options,
                          std::optional<CrackTracker>& crack, CrackAngleStream& angles, CrackAreaTracker* area,
                          std::vector<std::string>& notes) {
  const auto& snapshots = run.info.snapshots;
  const fs::path post(options.output_directory);
  VtuSeriesWriter writer(run.reference, options.compression);
  SeriesResult series;
  std::vector<PvdEntry>& entries = series.entries;
  Progress progress("postprocess", static_cast<std::int64_t>(snapshots.size()), options.quiet);
  if (first.snapshot.find("pore_pressure")) series.pore_pressure.emplace(run.reference);
  for (std::size_t k = 0; k < snapshots.size(); ++k) {
    Snapshot snapshot = k == 0 ? std::move(first.snapshot) : read_snapshot(snapshots[k].path);
    if (k == 0) first.snapshot = Snapshot{};
    check_snapshot(snapshot, run, snapshots[k], first.layout);
    const FrameArrays arrays = frame_arrays(snapshot, notes);
    const std::string file = frame_file_name(snapshots[k].step);
    writer.write_frame((post / kVtuDirectory / file).string(), snapshot.time, snapshot.step, arrays.arrays);
    entries.push_back({snapshot.time, std::string(kVtuDirectory) + "/" + file});
    // Rewritten as frames are added, so an interrupted series stays readable; for long series
    // only every ~1/64 of the way (rewriting after every frame would grow quadratically).
    const std::size_t every = std::max<std::size_t>(1, snapshots.size() / 64);
    if (k < 64 || (k + 1) % every == 0 || k + 1 == snapshots.size())
      write_text((post / "results.pvd").string(), pvd_text(entries));
    if (crack) crack->add_frame(snapshot.time, snapshot.find("damage")->data);
    angles.add(k, snapshot);
    if (const SnapshotField* p = snapshot.find("pore_pressure"); p && p->components == 1 && series.pore_pressure)
      series.pore_pressure->add_frame(snapshot.time, p->data);
    if (area) area->add_frame(snapshot.time, snapshot.find("crack_area")->data);
    if (const SnapshotField* e = snapshot.find("plastic_shear_strain"); e && e->components == 1) {
      series.last_plastic_shear = e->data;
      series.last_plastic_time = snapshot.time;
    }
    progress.update(static_cast<std::int64_t>(k + 1), format_time(snapshot.time));
  }
  progress.finish();
  return series;
}

// Names of the velocity and displacement boundaries of the scene.
std::vector<std::string> kinematic_boundary_names(const YAML::Node& scene) {
  std::vector<std::string> kinematic;
  if (const YAML::Node bcs = scene["boundary_conditions"]; bcs && bcs.IsSequence())
    for (const auto& bc : bcs) {
      const std::string type = bc["type"] ? bc["type"].as<std::string>() : "";
      if ((type == "velocity" || type == "displacement") && bc["name"])
        kinematic.push_back(bc["name"].as<std::string>());
    }
  return kinematic;
}

// Writes load_curve.csv; returns the peak load of the main kinematic boundary.
PeakLoad write_load_curve(const RunDirectory& run, const fs::path& post, std::vector<std::string>& notes) {
  const LoadTable table = read_load_table((fs::path(run.path) / run_layout::load).string());
  notes.insert(notes.end(), table.notes.begin(), table.notes.end());
  const LoadCurve curve = make_load_curve(table);
  write_text((post / "load_curve.csv").string(), load_curve_csv(curve));
  return find_peak_load(curve, kinematic_boundary_names(run.scene));
}

// The run's counts, material, boundary conditions and peak load: the first part of summary.json.
JsonValue run_summary(const RunDirectory& run, std::size_t frames, const std::vector<std::string>& array_names,
                      const PeakLoad& peak) {
  JsonValue summary = JsonValue::object();
  summary.set("run_directory", fs::absolute(run.path).lexically_normal().string());
  summary.set("status", run.info.status);
  if (!run.info.message.empty()) summary.set("message", run.info.message);
  summary.set("dimension", run.info.dimension);
  summary.set("points", run.info.points);
  summary.set("bonds", run.info.bonds);
  summary.set("steps", run.info.steps);
  summary.set("wall_seconds", run.info.wall_seconds);
  summary.set("threads", run.info.threads);
  auto effects = JsonValue::array();
  for (const auto& e : run.info.effects) effects.push(e);
  summary.set("effects", effects);
  summary.set("detached_points", run.info.detached_points);
  summary.set("snapshots", static_cast<std::int64_t>(frames));
  summary.set("first_time_s", run.info.snapshots.front().time);
  summary.set("last_time_s", run.info.snapshots.back().time);
  summary.set("spacing_m", run.spacing);
  summary.set("horizon_m", run.horizon);
  auto fields = JsonValue::array();
  for (const auto& name : array_names) fields.push(name);
  summary.set("fields", fields);
  summary.set("material", run.scene["material"] ? yaml_to_json(run.scene["material"]) : JsonValue());
  summary.set("boundary_conditions",
              run.scene["boundary_conditions"] ? yaml_to_json(run.scene["boundary_conditions"]) : JsonValue::array());
  summary.set("main_boundary", peak.boundary.empty() ? JsonValue() : JsonValue(peak.boundary));
  summary.set("main_axis", peak.boundary.empty() ? JsonValue() : JsonValue(std::string(1, "xyz"[peak.axis])));
  summary.set("peak_load_N", peak.peak_load_N);
  summary.set("displacement_at_peak_m", peak.displacement_at_peak_m);
  summary.set("time_at_peak_s", peak.time_at_peak_s);
  return summary;
}

void set_shear_band_entries(JsonValue& summary, const ShearBandResult& bands, double time) {
  auto angles = JsonValue::array(), widths = JsonValue::array();
  for (const auto& b : bands.bands) {
    angles.push(b.angle_deg);
    widths.push(b.width_m);
  }
  summary.set("shear_band_time_s", time);
  summary.set("shear_band_count", static_cast<std::int64_t>(bands.bands.size()));
  summary.set("shear_band_angle_deg", bands.mean_angle_deg);
  summary.set("shear_band_angles_deg", angles);
  summary.set("shear_band_width_m", bands.mean_width_m);
  summary.set("shear_band_widths_m", widths);
  // Each band's centre line as well, so a check can tell conjugate bands (one of positive,
  // one of negative slope) and find the points inside a band.
  auto details = JsonValue::array();
  for (const auto& b : bands.bands) {
    auto band = JsonValue::object();
    band.set("angle_deg", b.angle_deg);
    band.set("direction_deg", b.direction_deg);
    auto centre = JsonValue::array();
    centre.push(b.centre_x);
    centre.push(b.centre_y);
    band.set("centre_m", centre);
    band.set("width_m", b.width_m);
    band.set("points", static_cast<std::uint64_t>(b.points));
    details.push(band);
  }
  summary.set("shear_bands", details);
}

// Shear bands of the last plastic shear strain field (2-D runs), away from the boundary layers.
void add_shear_band_metrics(JsonValue& summary, std::vector<std::string>& notes, const RunDirectory& run,
                            const PointGeometry& points, const SeriesResult& series) {
  const bool has_plastic = !series.last_plastic_shear.empty();
  if (has_plastic && run.info.dimension == 2) {
    const std::vector<char> interior =
        points_away_from_boundaries(points.x, points.y, points.z, points.region, points.boundary_id, 2.0 * run.horizon);
    ShearBandSettings settings;
    settings.spacing = run.spacing;
    const ShearBandResult bands =
        measure_shear_bands(points.x, points.y, series.last_plastic_shear, interior, settings);
    set_shear_band_entries(summary, bands, series.last_plastic_time);
    if (!bands.note.empty()) notes.push_back("shear bands: " + bands.note);
  } else if (has_plastic) {
    notes.push_back("shear-band metrics are measured in 2-D runs only");
  }
}

// The frames of the crack tracker: from the crack-arrival table when the run has one, at the times
// the crack path changed (the snapshots then fed it none); else from the snapshots' damage fields.
CrackFrameSource crack_frame_source(std::optional<CrackTracker>& crack,
                                    const std::optional<std::vector<CrackArrival>>& table, const RunDirectory& run) {
  const auto& snapshots = run.info.snapshots;
  if (crack && table)
    return add_crack_path_frames(*crack, *table, snapshots.front().time, snapshots.back().time, run.info.time_step_s);
  CrackFrameSource source{"snapshots", 0.0, snapshots.size()};
  for (std::size_t k = 1; k < snapshots.size(); ++k)
    source.resolution_s = std::max(source.resolution_s, snapshots[k].time - snapshots[k - 1].time);
  // The difference of two snapshot times carries their rounding (2.500000000000061e-07 for a
  // 0.25 us interval): 12 digits are the interval.
  char digits[32];
  std::snprintf(digits, sizeof digits, "%.12g", source.resolution_s);
  source.resolution_s = std::strtod(digits, nullptr);
  return source;
}

// Where the crack metrics' frames came from, how fine they resolve an event, how many were tracked.
void set_crack_metrics_source(JsonValue& summary, const CrackFrameSource& source) {
  summary.set("crack_metrics_source", source.name);
  summary.set("crack_metrics_resolution_s", source.resolution_s);
  summary.set("crack_metrics_frames", static_cast<std::uint64_t>(source.frames));
}

// `area_metrics`: a 3-D run measured by its crack area instead (add_crack_area_metrics).
void add_crack_metrics(JsonValue& summary, std::vector<std::string>& notes, const RunDirectory& run,
                       const std::optional<CrackTracker>& crack, bool has_damage, bool area_metrics,
                       const CrackFrameSource& source) {
  if (crack) {
    const CrackMetrics m = crack->finish();
    set_crack_metrics_source(summary, source);
    summary.set("crack_start_time_s", m.start_time_s);
    summary.set("crack_branch_time_s", m.branch_time_s);
    summary.set("crack_end_time_s", m.end_time_s);
    summary.set("crack_end_reason", m.end_reason.empty() ? JsonValue() : JsonValue(m.end_reason));
    summary.set("crack_tip_speed_max_m_per_s", m.tip_speed_max_m_per_s);
    summary.set("crack_length_m", m.crack_length_m);
    summary.set("crack_damage_threshold", crack->damage_threshold());
    if (!m.note.empty()) notes.push_back("crack: " + m.note);
  } else if (has_damage ||
             std::find(run.info.effects.begin(), run.info.effects.end(), "damage") != run.info.effects.end()) {
    if (run.info.dimension == 2) return;
    notes.push_back(area_metrics
                        ? "crack branching, end, tip speed and length are measured in 2-D runs only (3-D runs: "
                          "crack area, start time and front advance; the crack angle on the mid-thickness layer)"
                        : "crack metrics are measured in 2-D runs, and in 3-D runs from the crack_area field, which "
                          "this run's snapshots do not hold (output.fields)");
  }
}

// 3-D: the crack area, its start and the front advance (crack_area_metrics.hpp), and
// crack_area.csv with their history.
void add_crack_area_metrics(JsonValue& summary, std::vector<std::string>& notes, const CrackAreaTracker& area,
                            const CrackFrameSource& source, const fs::path& post) {
  const CrackAreaMetrics m = area.finish();
  set_crack_metrics_source(summary, source);
  summary.set("crack_start_time_s", m.start_time_s);
  summary.set("crack_area_m2", m.area_m2);
  summary.set("crack_precrack_area_m2", m.precrack_area_m2);
  summary.set("crack_front_advance_m", m.front_advance_m);
  summary.set("crack_front_advance_time_s", m.front_advance_time_s);
  summary.set("crack_start_area_m2", area.start_area());
  summary.set("crack_front_point_area_m2", area.front_point_area());
  for (const auto& note : m.notes) notes.push_back("crack: " + note);
  write_text((post / "crack_area.csv").string(), crack_area_csv(m));
}

// The crack-angle options need a run with damage; given crack tips need a 2-D run and must lie in
// the body, and a measure time must have a snapshot at or before it: checked before anything is
// written.
void check_crack_angle_options(const CrackAngleSettings& settings, const RunDirectory& run, const PointGeometry& points,
                               bool has_damage) {
  if (settings.tips.empty() && !settings.range_from && !settings.measure_time) return;
  if (!has_damage)
    throw InputError(
        "--crack-tip, --crack-direction, --crack-angle-range and --crack-angle-time need a run with a damage field");
  if (!settings.tips.empty() && run.info.dimension != 2)
    throw InputError(
        "--crack-tip and --crack-direction need a 2-D run (a 3-D run's crack angles are measured on its "
        "mid-thickness layer, from the tips of its pre-crack)");
  check_crack_tips_in_body(settings.tips, points.x, points.y, points.z, points.body, run.horizon);
  if (settings.measure_time && !snapshot_at_or_before(run.info.snapshots, *settings.measure_time))
    throw InputError("--crack-angle-time: " + format_time(*settings.measure_time).substr(4) +
                     " is before the first snapshot (" + format_time(run.info.snapshots.front().time) +
                     "): the angle is measured on the last snapshot at or before it");
}

JsonValue json_vector(const Vector3& v) {
  auto array = JsonValue::array();
  for (double c : v) array.push(c);
  return array;
}

void set_crack_angle_entries(JsonValue& summary, const CrackAngleResult& result) {
  auto angles = JsonValue::array(), details = JsonValue::array();
  for (const auto& c : result.cracks) {
    angles.push(c.angle_deg);
    auto crack = JsonValue::object();
    crack.set("tip_index", static_cast<std::uint64_t>(c.tip_index));
    crack.set("crack_index", static_cast<std::uint64_t>(c.crack_index));
    crack.set("tip_m", json_vector(c.tip.position));
    crack.set("precrack_direction", json_vector(c.tip.direction));
    crack.set("signed_angle_deg", c.signed_angle_deg);
    crack.set("angle_deg", c.angle_deg);
    crack.set("fit_point_m", json_vector(c.fit_point));
    crack.set("fit_direction", json_vector(c.fit_direction));
    crack.set("points", static_cast<std::uint64_t>(c.points));
    crack.set("range_from_m", result.range_from);
    crack.set("range_to_m", result.range_to);
    crack.set("measured_at_s", c.measured_at_s);
    crack.set("reached_outer_radius", c.reached_outer_radius);
    details.push(crack);
  }
  summary.set("crack_angle_deg", angles);
  summary.set("crack_angles", details);
}

// The pore-pressure metrics (postprocess/README.md), when the snapshots have pore_pressure.
void add_pore_pressure_metrics(JsonValue& summary, const SeriesResult& series) {
  if (!series.pore_pressure) return;
  const auto m = series.pore_pressure->result();
  if (!m) return;
  auto position = [](const PressureExtreme& e) {
    auto v = JsonValue::array();
    for (double x : e.position) v.push(x);
    return v;
  };
  summary.set("pore_pressure_peak_Pa", m->peak.value);
  summary.set("pore_pressure_peak_time_s", m->peak.time);
  summary.set("pore_pressure_peak_m", position(m->peak));
  summary.set("pore_pressure_min_Pa", m->minimum.value);
  summary.set("pore_pressure_min_time_s", m->minimum.time);
  summary.set("pore_pressure_min_m", position(m->minimum));
  summary.set("pore_pressure_final_max_Pa", m->final_max);
  summary.set("pore_pressure_final_min_Pa", m->final_min);
  summary.set("pore_pressure_final_mean_Pa", m->final_mean);
}

void add_crack_angle_metrics(JsonValue& summary, std::vector<std::string>& notes, const CrackAngleStream& angles) {
  notes.insert(notes.end(), angles.notes.begin(), angles.notes.end());
  if (!angles.tracker) return;
  const CrackAngleResult result = angles.tracker->result();
  for (const auto& note : result.notes) notes.push_back("crack angle: " + note);
  if (angles.layer) {
    summary.set("crack_angle_layer_z_m", angles.layer->layer.z);
    notes.push_back("crack angle: measured on the mid-thickness layer z = " + format_length(angles.layer->layer.z) +
                    " (" + std::to_string(angles.layer->layer.points) + " body points)");
  }
  if (!result.tips.empty()) set_crack_angle_entries(summary, result);
}

}  // namespace

PostprocessResult postprocess_run(const PostprocessOptions& options) {
  PostprocessResult result;
  RunDirectory run = open_run_directory(options.run_directory, options.allow_unfinished);
  std::vector<std::string>& notes = result.notes;
  notes.insert(notes.end(), run.notes.begin(), run.notes.end());

  // Everything the options name is checked before anything is written.
  FirstSnapshot first = read_first_snapshot(run);
  const auto crack_table = read_crack_path_table(run.path, run.reference.point_count);
  const std::vector<std::string> figure_fields = choose_figure_fields(options.figure_fields, first);
  const std::vector<std::size_t> frames_for_figures = figure_frames(options.figure_times, run.info.snapshots);
  check_movie_field(options.movie_field, first);
  const ClipPlane clip = resolve_clip_plane(options.clip, run.reference, run.info.dimension);
  const PointGeometry points = point_geometry(run.reference);
  const bool has_damage = first.snapshot.find("damage") != nullptr;
  check_crack_angle_options(options.crack_angle, run, points, has_damage);
  const EarlierOutputRemoval earlier_output = prepare_post_directory(options);
  const fs::path post(options.output_directory);

  const bool crack_data = has_damage || crack_table.has_value();  // damage snapshots or the table
  std::optional<CrackTracker> crack = crack_tracker(run, points, crack_data && run.info.dimension == 2);
  CrackAngleStream angles = crack_angle_stream(run, points, first, crack, options.crack_angle);
  std::optional<CrackAreaTracker> area;  // 3-D damage runs, from their crack_area field
  if (run.info.dimension == 3 && first.snapshot.find("crack_area"))
    area.emplace(points.x, points.y, points.z, points.body, run.spacing);
  std::optional<CrackTracker> no_tracker;  // the table gives the frames
  const SeriesResult series =
      write_series(run, first, options, crack_table ? no_tracker : crack, angles, area ? &*area : nullptr, notes);
  const CrackFrameSource crack_source = crack_frame_source(crack, crack_table, run);
  result.frames = series.entries.size();

  const PeakLoad peak = write_load_curve(run, post, notes);
  JsonValue summary = run_summary(run, series.entries.size(), first.array_names, peak);
  add_shear_band_metrics(summary, notes, run, points, series);
  add_crack_metrics(summary, notes, run, crack, crack_data, area.has_value(), crack_source);
  if (area) add_crack_area_metrics(summary, notes, *area, crack_source, post);
  add_crack_angle_metrics(summary, notes, angles);
  add_pore_pressure_metrics(summary, series);
  auto note_array = JsonValue::array();
  for (const auto& note : notes) note_array.push(note);
  summary.set("notes", note_array);
  write_text((post / "summary.json").string(), summary.dump());
  result.summary = summary;
  write_paraview_state(options.output_directory,
                       {view_field(first.array_names), options.warp_scale, run.spacing, run.info.dimension});

  if (options.plot_load_curve) plot_load_curve(options.output_directory, peak.boundary, options.script_directory);
  const FigureSettings settings{run.spacing, run.info.dimension, options.warp_scale, options.script_directory, clip};
  const auto frame = [&](std::size_t k) {
    return FigureFrame{series.entries[k].file, run.info.snapshots[k].step, format_time(run.info.snapshots[k].time)};
  };
  if (options.figures) {
    std::vector<FigureFrame> frames;
    for (std::size_t k : frames_for_figures) frames.push_back(frame(k));
    result.figures = render_figures(options.output_directory, settings, frames, figure_fields);
  }
  if (!options.movie_field.empty()) {
    std::vector<FigureFrame> frames;
    for (std::size_t k = 0; k < series.entries.size(); ++k) frames.push_back(frame(k));
    result.movie =
        render_movie(options.output_directory, settings, frames, options.movie_field, options.clip.has_value());
  }
  return result;
}

}  // namespace mppm::post
