// POINTS.vtp: the VTK XML PolyData file that carries material points from the preprocessor to
// the solver (SCENE.md "Files between stages"). Binary appended, zlib-compressed, written
// atomically; the reader trusts nothing and names the file and the problem in every error.
#include "common/point_cloud.hpp"

#include <vtkCellArray.h>
#include <vtkCommand.h>
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
#include <vtkXMLPolyDataReader.h>
#include <vtkXMLPolyDataWriter.h>

#include <cmath>
#include <filesystem>
#include <sstream>

#include "common/atomic_file.hpp"
#include "common/input_error.hpp"

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

}  // namespace

void write_point_cloud(const PointCloud& cloud, const std::string& path) {
  const auto n = static_cast<vtkIdType>(cloud.size());
  vtkNew<vtkPolyData> poly;
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(n);
  for (vtkIdType i = 0; i < n; ++i) points->SetPoint(i, cloud.x[i], cloud.y[i], cloud.z[i]);
  poly->SetPoints(points);

  // One vertex cell per point so that ParaView shows the points without a glyph filter.
  vtkNew<vtkIdTypeArray> offsets, connectivity;
  offsets->SetNumberOfValues(n + 1);
  connectivity->SetNumberOfValues(n);
  for (vtkIdType i = 0; i <= n; ++i) offsets->SetValue(i, i);
  for (vtkIdType i = 0; i < n; ++i) connectivity->SetValue(i, i);
  vtkNew<vtkCellArray> vertices;
  vertices->SetData(offsets, connectivity);
  poly->SetVerts(vertices);

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

  vtkFieldData* field = poly->GetFieldData();
  vtkNew<vtkIntArray> dimension;
  dimension->SetName("dimension");
  dimension->InsertNextValue(cloud.dimension);
  field->AddArray(dimension);
  field->AddArray(scalar_field("spacing", cloud.spacing));
  field->AddArray(scalar_field("horizon", cloud.horizon));
  field->AddArray(scalar_field("thickness", cloud.thickness));
  vtkNew<vtkStringArray> names, types;
  names->SetName("boundary_names");
  types->SetName("boundary_types");
  vtkNew<vtkDoubleArray> areas;
  areas->SetName("boundary_areas");
  vtkNew<vtkTypeInt64Array> counts;
  counts->SetName("boundary_point_counts");
  for (const BoundaryInfo& b : cloud.boundaries) {
    names->InsertNextValue(b.name);
    types->InsertNextValue(b.type);
    areas->InsertNextValue(b.area);
    counts->InsertNextValue(b.point_count);
  }
  vtkNew<vtkIntArray> boundary_count;
  boundary_count->SetName("boundary_count");
  boundary_count->InsertNextValue(static_cast<int>(cloud.boundaries.size()));
  field->AddArray(boundary_count);
  if (!cloud.boundaries.empty()) {
    field->AddArray(names);
    field->AddArray(types);
    field->AddArray(areas);
    field->AddArray(counts);
  }
  vtkNew<vtkDoubleArray> precrack;
  precrack->SetName("precrack_vertices");
  precrack->SetNumberOfComponents(3);
  precrack->SetNumberOfTuples(static_cast<vtkIdType>(cloud.precrack_vertices.size() / 3));
  for (std::size_t i = 0; i < cloud.precrack_vertices.size(); ++i)
    precrack->SetValue(static_cast<vtkIdType>(i), cloud.precrack_vertices[i]);
  field->AddArray(precrack);

  vtkNew<vtkXMLPolyDataWriter> writer;
  writer->SetInputData(poly);
  writer->SetDataModeToAppended();
  writer->EncodeAppendedDataOff();  // raw binary: smaller and faster than base64
  writer->SetCompressorTypeToZLib();
  writer->SetCompressionLevel(1);  // most of the size gain at a fraction of the time
  writer->SetHeaderTypeToUInt64();  // no 4 GiB limit per array
  writer->WriteToOutputStringOn();
  if (writer->Write() != 1) throw InputError(path + ": VTK could not encode the point cloud");
  const std::string encoded = writer->GetOutputString();
  write_file_atomically(path, [&](std::ostream& out) { out.write(encoded.data(), static_cast<std::streamsize>(encoded.size())); });
}

namespace {

// Collects VTK's error messages instead of letting them go to the terminal.
class ErrorCollector : public vtkCommand {
 public:
  static ErrorCollector* New() { return new ErrorCollector; }
  void Execute(vtkObject*, unsigned long, void* data) override {
    if (message.empty() && data) message = static_cast<const char*>(data);
  }
  std::string message;
};

[[noreturn]] void fail(const std::string& path, const std::string& problem) {
  throw InputError(path + ": " + problem);
}

vtkDataArray* required_array(vtkFieldData* data, const char* name, vtkIdType tuples,
                             int components, const std::string& path, const char* where) {
  vtkDataArray* array = data ? vtkDataArray::SafeDownCast(data->GetAbstractArray(name)) : nullptr;
  if (!array) fail(path, std::string("missing ") + where + " array '" + name + "'");
  if (array->GetNumberOfComponents() != components || array->GetNumberOfTuples() != tuples) {
    std::ostringstream s;
    s << where << " array '" << name << "' has " << array->GetNumberOfTuples() << " x "
      << array->GetNumberOfComponents() << " values (expected " << tuples << " x " << components
      << ")";
    fail(path, s.str());
  }
  return array;
}

double finite_value(vtkDataArray* array, vtkIdType i, int c, const std::string& path) {
  const double value = array->GetComponent(i, c);
  if (!std::isfinite(value))
    fail(path, std::string("array '") + array->GetName() + "' has a non-finite value at index " +
                   std::to_string(i));
  return value;
}

std::int32_t integer_value(vtkDataArray* array, vtkIdType i, const std::string& path) {
  const double value = finite_value(array, i, 0, path);
  if (value != std::floor(value) || std::abs(value) > 2e9)
    fail(path, std::string("array '") + array->GetName() + "' has a non-integer value at index " +
                   std::to_string(i));
  return static_cast<std::int32_t>(value);
}

double field_scalar(vtkFieldData* field, const char* name, const std::string& path) {
  return finite_value(required_array(field, name, 1, 1, path, "field data"), 0, 0, path);
}

}  // namespace

PointCloud read_point_cloud(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    fail(path, "points file not found (run mppm-preprocess first)");
  vtkNew<vtkXMLPolyDataReader> reader;
  vtkNew<ErrorCollector> errors;
  reader->AddObserver(vtkCommand::ErrorEvent, errors);
  reader->AddObserver(vtkCommand::WarningEvent, errors);
  if (!reader->CanReadFile(path.c_str()))
    fail(path, "not a VTK XML PolyData file (expected POINTS.vtp written by mppm-preprocess)");
  reader->SetFileName(path.c_str());
  reader->Update();
  if (reader->GetErrorCode() != 0 || !errors->message.empty())
    fail(path, "unreadable VTK XML PolyData (" +
                   (errors->message.empty() ? std::string("read error") : errors->message) + ")");
  vtkPolyData* poly = reader->GetOutput();
  if (!poly || !poly->GetPoints()) fail(path, "no points");

  PointCloud cloud;
  vtkFieldData* field = poly->GetFieldData();
  const double dimension = field_scalar(field, "dimension", path);
  if (dimension != 2 && dimension != 3) fail(path, "field 'dimension' must be 2 or 3");
  cloud.dimension = static_cast<int>(dimension);
  cloud.spacing = field_scalar(field, "spacing", path);
  cloud.horizon = field_scalar(field, "horizon", path);
  cloud.thickness = field_scalar(field, "thickness", path);
  if (!(cloud.spacing > 0)) fail(path, "field 'spacing' must be positive");
  if (!(cloud.horizon >= cloud.spacing))
    fail(path, "field 'horizon' must be at least the spacing");
  if (!(cloud.thickness > 0)) fail(path, "field 'thickness' must be positive");

  const vtkIdType n = poly->GetNumberOfPoints();
  if (n <= 0) fail(path, "no points");
  cloud.resize(static_cast<std::size_t>(n));
  vtkPointData* pd = poly->GetPointData();
  vtkDataArray* volume = required_array(pd, "volume", n, 1, path, "point");
  vtkDataArray* region = required_array(pd, "region", n, 1, path, "point");
  vtkDataArray* boundary_id = required_array(pd, "boundary_id", n, 1, path, "point");
  vtkDataArray* normal = required_array(pd, "normal", n, 3, path, "point");

  const auto boundary_count =
      static_cast<std::int32_t>(field_scalar(field, "boundary_count", path));
  if (boundary_count < 0) fail(path, "field 'boundary_count' must not be negative");
  if (boundary_count > 0) {
    auto* names = vtkStringArray::SafeDownCast(field->GetAbstractArray("boundary_names"));
    auto* types = vtkStringArray::SafeDownCast(field->GetAbstractArray("boundary_types"));
    if (!names || names->GetNumberOfValues() != boundary_count)
      fail(path, "field 'boundary_names' missing or not one name per boundary");
    if (!types || types->GetNumberOfValues() != boundary_count)
      fail(path, "field 'boundary_types' missing or not one type per boundary");
    vtkDataArray* areas = required_array(field, "boundary_areas", boundary_count, 1, path, "field data");
    vtkDataArray* counts =
        required_array(field, "boundary_point_counts", boundary_count, 1, path, "field data");
    for (vtkIdType k = 0; k < boundary_count; ++k) {
      BoundaryInfo info;
      info.name = names->GetValue(k);
      info.type = types->GetValue(k);
      if (info.type != "velocity" && info.type != "displacement" && info.type != "traction" &&
          info.type != "pressure")
        fail(path, "boundary '" + info.name + "' has unknown type '" + info.type + "'");
      info.area = finite_value(areas, k, 0, path);
      info.point_count = static_cast<std::int64_t>(finite_value(counts, k, 0, path));
      cloud.boundaries.push_back(info);
    }
  }

  vtkPoints* points = poly->GetPoints();
  for (vtkIdType i = 0; i < n; ++i) {
    double p[3];
    points->GetPoint(i, p);
    if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2]))
      fail(path, "point " + std::to_string(i) + " has a non-finite coordinate");
    if (cloud.dimension == 2 && p[2] != 0.0)
      fail(path, "point " + std::to_string(i) + " has z != 0 in a 2-D cloud");
    cloud.x[i] = p[0];
    cloud.y[i] = p[1];
    cloud.z[i] = p[2];
    cloud.volume[i] = finite_value(volume, i, 0, path);
    if (!(cloud.volume[i] > 0)) fail(path, "point " + std::to_string(i) + " has volume <= 0");
    cloud.region[i] = integer_value(region, i, path);
    cloud.boundary_id[i] = integer_value(boundary_id, i, path);
    if (cloud.region[i] < 0 || cloud.region[i] > boundary_count)
      fail(path, "point " + std::to_string(i) + " has region " + std::to_string(cloud.region[i]) +
                     " (expected 0.." + std::to_string(boundary_count) + ")");
    if (cloud.boundary_id[i] < 0 || cloud.boundary_id[i] > boundary_count)
      fail(path, "point " + std::to_string(i) + " has boundary_id " +
                     std::to_string(cloud.boundary_id[i]) + " (expected 0.." +
                     std::to_string(boundary_count) + ")");
    if (cloud.region[i] > 0 && cloud.boundary_id[i] != cloud.region[i])
      fail(path, "layer point " + std::to_string(i) + " has boundary_id != region");
    cloud.normal_x[i] = finite_value(normal, i, 0, path);
    cloud.normal_y[i] = finite_value(normal, i, 1, path);
    cloud.normal_z[i] = finite_value(normal, i, 2, path);
  }

  auto* precrack = vtkDataArray::SafeDownCast(field->GetAbstractArray("precrack_vertices"));
  if (precrack) {
    if (precrack->GetNumberOfComponents() != 3)
      fail(path, "field 'precrack_vertices' must have 3 components");
    const vtkIdType vertices = precrack->GetNumberOfTuples();
    if (vertices % cloud.precrack_vertices_per_element() != 0)
      fail(path, "field 'precrack_vertices' is not a whole number of " +
                     std::string(cloud.dimension == 2 ? "segments" : "triangles"));
    cloud.precrack_vertices.resize(static_cast<std::size_t>(vertices) * 3);
    for (vtkIdType v = 0; v < vertices; ++v)
      for (int c = 0; c < 3; ++c)
        cloud.precrack_vertices[static_cast<std::size_t>(v) * 3 + c] =
            finite_value(precrack, v, c, path);
  }
  return cloud;
}

}  // namespace mppm
