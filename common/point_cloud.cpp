// POINTS.vtp: the VTK XML PolyData file that carries material points from the preprocessor to
// the solver (docs/stages.md "Files between stages"). Binary appended, zlib-compressed, written
// atomically by VTK's writer; read by our strict reader (vtk_xml_reader.hpp), which trusts
// nothing and names the file and the problem in every error.
#include "common/point_cloud.hpp"

#include <vtkCellArray.h>
#include <vtkDataArray.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkIdTypeArray.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkStringArray.h>
#include <vtkTypeInt64Array.h>
#include <vtkXMLPolyDataWriter.h>

#include <cmath>
#include <filesystem>
#include <set>
#include <sstream>

#include "common/atomic_file.hpp"
#include "common/input_error.hpp"
#include "common/vtk_xml_reader.hpp"

namespace mppm {

void PointCloud::resize(std::size_t n) {
  x.resize(n);
  y.resize(n);
  z.resize(n);
  volume.resize(n);
  region.resize(n);
  boundary_id.resize(n);
  normal_x.resize(n);
  normal_y.resize(n);
  normal_z.resize(n);
}

namespace {

vtkNew<vtkDoubleArray> scalar_field(const char* name, double value) {
  vtkNew<vtkDoubleArray> array;
  array->SetName(name);
  array->InsertNextValue(value);
  return array;
}

// One vertex cell per point so that ParaView shows the points without a glyph filter.
void add_vertex_cells(vtkPolyData* poly, vtkIdType n) {
  vtkNew<vtkIdTypeArray> offsets, connectivity;
  offsets->SetNumberOfValues(n + 1);
  connectivity->SetNumberOfValues(n);
  for (vtkIdType i = 0; i <= n; ++i) offsets->SetValue(i, i);
  for (vtkIdType i = 0; i < n; ++i) connectivity->SetValue(i, i);
  vtkNew<vtkCellArray> vertices;
  vertices->SetData(offsets, connectivity);
  poly->SetVerts(vertices);
}

// volume, region, boundary_id and normal of each point.
void add_point_arrays(vtkPolyData* poly, const PointCloud& cloud, vtkIdType n) {
  vtkNew<vtkDoubleArray> volume;
  volume->SetName("volume");
  volume->SetNumberOfValues(n);
  vtkNew<vtkIntArray> region, boundary_id;
  region->SetName("region");
  region->SetNumberOfValues(n);
  boundary_id->SetName("boundary_id");
  boundary_id->SetNumberOfValues(n);
  vtkNew<vtkDoubleArray> normal;
  normal->SetName("normal");
  normal->SetNumberOfComponents(3);
  normal->SetNumberOfTuples(n);
  for (vtkIdType i = 0; i < n; ++i) {
    volume->SetValue(i, cloud.volume[i]);
    region->SetValue(i, cloud.region[i]);
    boundary_id->SetValue(i, cloud.boundary_id[i]);
    normal->SetTuple3(i, cloud.normal_x[i], cloud.normal_y[i], cloud.normal_z[i]);
  }
  poly->GetPointData()->AddArray(volume);
  poly->GetPointData()->AddArray(region);
  poly->GetPointData()->AddArray(boundary_id);
  poly->GetPointData()->AddArray(normal);
}

// boundary_count, then (if there are boundaries) one value per boundary in each boundary_* array.
void add_boundary_arrays(vtkFieldData* field, const std::vector<BoundaryInfo>& boundaries) {
  vtkNew<vtkStringArray> names, types;
  names->SetName("boundary_names");
  types->SetName("boundary_types");
  vtkNew<vtkDoubleArray> areas;
  areas->SetName("boundary_areas");
  vtkNew<vtkTypeInt64Array> counts;
  counts->SetName("boundary_point_counts");
  vtkNew<vtkStringArray> selectors;
  selectors->SetName("boundary_selectors");
  vtkNew<vtkDoubleArray> depths;
  depths->SetName("boundary_depths");
  for (const BoundaryInfo& b : boundaries) {
    names->InsertNextValue(b.name);
    types->InsertNextValue(b.type);
    areas->InsertNextValue(b.area);
    counts->InsertNextValue(b.point_count);
    selectors->InsertNextValue(b.selector);
    depths->InsertNextValue(b.depth);
  }
  vtkNew<vtkIntArray> boundary_count;
  boundary_count->SetName("boundary_count");
  boundary_count->InsertNextValue(static_cast<int>(boundaries.size()));
  field->AddArray(boundary_count);
  if (!boundaries.empty()) {
    field->AddArray(names);
    field->AddArray(types);
    field->AddArray(areas);
    field->AddArray(counts);
    field->AddArray(selectors);
    field->AddArray(depths);
  }
}

// The cloud's scalars, its boundaries and the pre-crack vertices, as field data.
void add_field_data(vtkPolyData* poly, const PointCloud& cloud) {
  vtkFieldData* field = poly->GetFieldData();
  vtkNew<vtkIntArray> dimension;
  dimension->SetName("dimension");
  dimension->InsertNextValue(cloud.dimension);
  field->AddArray(dimension);
  field->AddArray(scalar_field("spacing", cloud.spacing));
  field->AddArray(scalar_field("horizon", cloud.horizon));
  field->AddArray(scalar_field("thickness", cloud.thickness));
  add_boundary_arrays(field, cloud.boundaries);
  vtkNew<vtkDoubleArray> precrack;
  precrack->SetName("precrack_vertices");
  precrack->SetNumberOfComponents(3);
  precrack->SetNumberOfTuples(static_cast<vtkIdType>(cloud.precrack_vertices.size() / 3));
  for (std::size_t i = 0; i < cloud.precrack_vertices.size(); ++i)
    precrack->SetValue(static_cast<vtkIdType>(i), cloud.precrack_vertices[i]);
  field->AddArray(precrack);
}

}  // namespace

std::optional<std::size_t> shared_boundary(const std::vector<BoundaryInfo>& boundaries, std::size_t k) {
  const BoundaryInfo& fluid = boundaries[k];
  if (fluid.point_count != 0 || fluid.selector.empty()) return std::nullopt;
  auto kinematic = [](const std::string& t) { return t == "velocity" || t == "displacement"; };
  auto loaded = [](const std::string& t) { return t == "traction" || t == "pressure"; };
  for (std::size_t j = 0; j < boundaries.size(); ++j) {
    const BoundaryInfo& other = boundaries[j];
    if (j == k || other.selector != fluid.selector || other.point_count == 0) continue;
    if ((fluid.type == "pore_pressure" && kinematic(other.type)) || (fluid.type == "fluid_flux" && loaded(other.type)))
      return j;
  }
  return std::nullopt;
}

void write_point_cloud(const PointCloud& cloud, const std::string& path) {
  const auto n = static_cast<vtkIdType>(cloud.size());
  vtkNew<vtkPolyData> poly;
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(n);
  for (vtkIdType i = 0; i < n; ++i) points->SetPoint(i, cloud.x[i], cloud.y[i], cloud.z[i]);
  poly->SetPoints(points);
  add_vertex_cells(poly, n);
  add_point_arrays(poly, cloud, n);
  add_field_data(poly, cloud);

  vtkNew<vtkXMLPolyDataWriter> writer;
  writer->SetInputData(poly);
  writer->SetDataModeToAppended();
  writer->EncodeAppendedDataOff();  // raw binary: smaller and faster than base64
  writer->SetCompressorTypeToZLib();
  writer->SetCompressionLevel(1);   // most of the size gain at a fraction of the time
  writer->SetHeaderTypeToUInt64();  // no 4 GiB limit per array
  writer->WriteToOutputStringOn();
  if (writer->Write() != 1) throw InputError(path + ": VTK could not encode the point cloud");
  const std::string encoded = writer->GetOutputString();
  write_file_atomically(
      path, [&](std::ostream& out) { out.write(encoded.data(), static_cast<std::streamsize>(encoded.size())); });
}

namespace {

[[noreturn]] void fail(const std::string& path, const std::string& problem) { throw InputError(path + ": " + problem); }

const VtkArray& required_array(const VtkArray* array, const char* name, std::int64_t tuples, int components,
                               const std::string& path, const char* where) {
  if (!array) fail(path, std::string("missing ") + where + " array '" + name + "'");
  if (array->is_string()) fail(path, std::string(where) + " array '" + name + "' must be numeric");
  if (array->components != components || array->tuples != tuples) {
    std::ostringstream s;
    s << where << " array '" << name << "' has " << array->tuples << " x " << array->components << " values (expected "
      << tuples << " x " << components << ")";
    fail(path, s.str());
  }
  return *array;
}

double finite_value(const VtkArray& array, std::int64_t i, int c, const std::string& path) {
  const double value = array.numbers[static_cast<std::size_t>(i * array.components + c)];
  if (!std::isfinite(value))
    fail(path, "array '" + array.name + "' has a non-finite value at index " + std::to_string(i));
  return value;
}

std::int32_t integer_value(const VtkArray& array, std::int64_t i, const std::string& path) {
  const double value = finite_value(array, i, 0, path);
  if (value != std::floor(value) || std::abs(value) > 2e9)
    fail(path, "array '" + array.name + "' has a non-integer value at index " + std::to_string(i));
  return static_cast<std::int32_t>(value);
}

double field_scalar(const VtkPolyDataArrays& file, const char* name, const std::string& path) {
  return finite_value(required_array(file.field(name), name, 1, 1, path, "field data"), 0, 0, path);
}

const std::vector<std::string>& string_array(const VtkPolyDataArrays& file, const char* name, std::int64_t count,
                                             const char* what, const std::string& path) {
  const VtkArray* array = file.field(name);
  if (!array || !array->is_string() || static_cast<std::int64_t>(array->strings.size()) != count)
    fail(path, std::string("field '") + name + "' missing or not one " + what + " per boundary");
  return array->strings;
}

// dimension, spacing, horizon and thickness.
void read_cloud_scalars(const VtkPolyDataArrays& file, const std::string& path, PointCloud& cloud) {
  const double dimension = field_scalar(file, "dimension", path);
  if (dimension != 2 && dimension != 3) fail(path, "field 'dimension' must be 2 or 3");
  cloud.dimension = static_cast<int>(dimension);
  cloud.spacing = field_scalar(file, "spacing", path);
  cloud.horizon = field_scalar(file, "horizon", path);
  cloud.thickness = field_scalar(file, "thickness", path);
  if (!(cloud.spacing > 0)) fail(path, "field 'spacing' must be positive");
  if (!(cloud.horizon >= cloud.spacing)) fail(path, "field 'horizon' must be at least the spacing");
  if (!(cloud.thickness > 0)) fail(path, "field 'thickness' must be positive");
}

std::vector<BoundaryInfo> read_boundaries(const VtkPolyDataArrays& file, const std::string& path) {
  const double boundary_count_value = field_scalar(file, "boundary_count", path);
  if (boundary_count_value < 0 || boundary_count_value > 1e6 ||
      boundary_count_value != std::floor(boundary_count_value))
    fail(path, "field 'boundary_count' must be a whole number from 0 to 1000000");
  const auto boundary_count = static_cast<std::int32_t>(boundary_count_value);
  std::vector<BoundaryInfo> boundaries;
  if (boundary_count == 0) return boundaries;
  const auto& names = string_array(file, "boundary_names", boundary_count, "name", path);
  const auto& types = string_array(file, "boundary_types", boundary_count, "type", path);
  const VtkArray& areas =
      required_array(file.field("boundary_areas"), "boundary_areas", boundary_count, 1, path, "field data");
  const VtkArray& counts = required_array(file.field("boundary_point_counts"), "boundary_point_counts", boundary_count,
                                          1, path, "field data");
  // Optional (files from before they were stored): what each layer was made from.
  const bool has_origin = file.field("boundary_selectors") || file.field("boundary_depths");
  const std::vector<std::string>* selectors =
      has_origin ? &string_array(file, "boundary_selectors", boundary_count, "selection", path) : nullptr;
  const VtkArray* depths = has_origin ? &required_array(file.field("boundary_depths"), "boundary_depths",
                                                        boundary_count, 1, path, "field data")
                                      : nullptr;
  for (std::int32_t k = 0; k < boundary_count; ++k) {
    BoundaryInfo info;
    info.name = names[static_cast<std::size_t>(k)];
    info.type = types[static_cast<std::size_t>(k)];
    static const std::set<std::string> known{"velocity", "displacement",  "traction",
                                             "pressure", "pore_pressure", "fluid_flux"};
    if (!known.count(info.type)) fail(path, "boundary '" + info.name + "' has unknown type '" + info.type + "'");
    info.area = finite_value(areas, k, 0, path);
    const double point_count = finite_value(counts, k, 0, path);
    if (point_count < 0 || point_count > 9e15 || point_count != std::floor(point_count))
      fail(path, "boundary '" + info.name + "' has a bad point count");
    info.point_count = static_cast<std::int64_t>(point_count);
    if (has_origin) {
      info.selector = (*selectors)[static_cast<std::size_t>(k)];
      info.depth = finite_value(*depths, k, 0, path);
      if (info.depth < 0) fail(path, "boundary '" + info.name + "' has a negative depth");
    }
    boundaries.push_back(info);
  }
  return boundaries;
}

// The per-point arrays of the file, checked for their length.
struct PointArrays {
  const VtkArray& volume;
  const VtkArray& region;
  const VtkArray& boundary_id;
  const VtkArray& normal;
};

// Positions and point arrays into the (sized) cloud, each value checked; regions and boundary
// ids against the cloud's boundaries.
void read_points(const VtkArray& points, const PointArrays& arrays, const std::string& path, PointCloud& cloud) {
  const auto n = static_cast<std::int64_t>(cloud.size());
  const auto boundary_count = static_cast<std::int32_t>(cloud.boundaries.size());
  for (std::int64_t i = 0; i < n; ++i) {
    const auto u = static_cast<std::size_t>(i);
    const double p[3] = {points.numbers[3 * u], points.numbers[3 * u + 1], points.numbers[3 * u + 2]};
    if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2]))
      fail(path, "point " + std::to_string(i) + " has a non-finite coordinate");
    if (cloud.dimension == 2 && p[2] != 0.0) fail(path, "point " + std::to_string(i) + " has z != 0 in a 2-D cloud");
    cloud.x[u] = p[0];
    cloud.y[u] = p[1];
    cloud.z[u] = p[2];
    cloud.volume[u] = finite_value(arrays.volume, i, 0, path);
    if (!(cloud.volume[u] > 0)) fail(path, "point " + std::to_string(i) + " has volume <= 0");
    cloud.region[u] = integer_value(arrays.region, i, path);
    cloud.boundary_id[u] = integer_value(arrays.boundary_id, i, path);
    if (cloud.region[u] < 0 || cloud.region[u] > boundary_count)
      fail(path, "point " + std::to_string(i) + " has region " + std::to_string(cloud.region[u]) + " (expected 0.." +
                     std::to_string(boundary_count) + ")");
    if (cloud.boundary_id[u] < 0 || cloud.boundary_id[u] > boundary_count)
      fail(path, "point " + std::to_string(i) + " has boundary_id " + std::to_string(cloud.boundary_id[u]) +
                     " (expected 0.." + std::to_string(boundary_count) + ")");
    if (cloud.region[u] > 0 && cloud.boundary_id[u] != cloud.region[u])
      fail(path, "layer point " + std::to_string(i) + " has boundary_id != region");
    cloud.normal_x[u] = finite_value(arrays.normal, i, 0, path);
    cloud.normal_y[u] = finite_value(arrays.normal, i, 1, path);
    cloud.normal_z[u] = finite_value(arrays.normal, i, 2, path);
  }
}

void read_precrack_vertices(const VtkPolyDataArrays& file, const std::string& path, PointCloud& cloud) {
  const VtkArray* precrack = file.field("precrack_vertices");
  if (!precrack) return;
  if (precrack->is_string() || precrack->components != 3)
    fail(path, "field 'precrack_vertices' must have 3 components");
  const std::int64_t vertices = precrack->tuples;
  if (vertices % cloud.precrack_vertices_per_element() != 0)
    fail(path, "field 'precrack_vertices' is not a whole number of " +
                   std::string(cloud.dimension == 2 ? "segments" : "triangles"));
  cloud.precrack_vertices.resize(static_cast<std::size_t>(vertices) * 3);
  for (std::int64_t v = 0; v < vertices; ++v)
    for (int c = 0; c < 3; ++c)
      cloud.precrack_vertices[static_cast<std::size_t>(v) * 3 + static_cast<std::size_t>(c)] =
          finite_value(*precrack, v, c, path);
}

}  // namespace

// The file is parsed by our own strict reader (vtk_xml_reader.hpp), not by VTK's XML reader,
// which crashes on some corrupted files (tests/fuzz/README.md).
PointCloud read_point_cloud(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) fail(path, "points file not found (run mppm-preprocess first)");
  const VtkPolyDataArrays file = read_vtk_polydata_arrays(path);

  PointCloud cloud;
  read_cloud_scalars(file, path, cloud);
  const std::int64_t n = file.point_count;
  if (n <= 0) fail(path, "no points");
  cloud.resize(static_cast<std::size_t>(n));
  const PointArrays arrays{required_array(file.point("volume"), "volume", n, 1, path, "point"),
                           required_array(file.point("region"), "region", n, 1, path, "point"),
                           required_array(file.point("boundary_id"), "boundary_id", n, 1, path, "point"),
                           required_array(file.point("normal"), "normal", n, 3, path, "point")};
  cloud.boundaries = read_boundaries(file, path);
  read_points(file.points, arrays, path, cloud);
  read_precrack_vertices(file, path, cloud);
  return cloud;
}

}  // namespace mppm
