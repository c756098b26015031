// VTK XML output. The points and vertex cells are built once and shared by every frame; frame
// arrays wrap the caller's memory (no copy), so a million-point frame costs little beyond the
// snapshot itself.
#include "postprocess/vtu_series_writer.hpp"

#include <vtkCellArray.h>
#include <vtkCellType.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkIdTypeArray.h>
#include <vtkIntArray.h>
#include <vtkLZ4DataCompressor.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkSmartPointer.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLUnstructuredGridWriter.h>
#include <vtkZLibDataCompressor.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>

#include "common/atomic_file.hpp"
#include "common/input_error.hpp"

namespace mppm::post {

struct VtuSeriesWriter::Impl {
  vtkSmartPointer<vtkPoints> points;
  vtkSmartPointer<vtkCellArray> cells;
  std::vector<vtkSmartPointer<vtkDataArray>> reference_arrays;
  VtuCompression compression = VtuCompression::zlib;
  vtkIdType count = 0;
};

VtuSeriesWriter::VtuSeriesWriter(const Snapshot& reference, VtuCompression compression)
    : impl_(std::make_unique<Impl>()) {
  impl_->compression = compression;
  const auto n = static_cast<vtkIdType>(reference.point_count);
  impl_->count = n;
  const SnapshotField* position = reference.find("position");
  if (!position || position->components != 3) throw InputError("reference snapshot: no 3-component position");
  vtkNew<vtkDoubleArray> coordinates;
  coordinates->SetNumberOfComponents(3);
  coordinates->SetNumberOfTuples(n);
  std::copy(position->data.begin(), position->data.end(), coordinates->GetPointer(0));
  impl_->points = vtkSmartPointer<vtkPoints>::New();
  impl_->points->SetData(coordinates);

  vtkNew<vtkIdTypeArray> offsets, connectivity;
  offsets->SetNumberOfTuples(n + 1);
  connectivity->SetNumberOfTuples(n);
  for (vtkIdType i = 0; i < n; ++i) {
    offsets->SetValue(i, i);
    connectivity->SetValue(i, i);
  }
  offsets->SetValue(n, n);
  impl_->cells = vtkSmartPointer<vtkCellArray>::New();
  impl_->cells->SetData(offsets, connectivity);

  // Reference arrays: volume (double), region and boundary_id (integers, for thresholds).
  if (const SnapshotField* volume = reference.find("volume")) {
    auto array = vtkSmartPointer<vtkDoubleArray>::New();
    array->SetName("volume");
    array->SetNumberOfTuples(n);
    std::copy(volume->data.begin(), volume->data.end(), array->GetPointer(0));
    impl_->reference_arrays.push_back(array);
  }
  for (const char* name : {"region", "boundary_id"})
    if (const SnapshotField* field = reference.find(name)) {
      auto array = vtkSmartPointer<vtkIntArray>::New();
      array->SetName(name);
      array->SetNumberOfTuples(n);
      for (vtkIdType i = 0; i < n; ++i)
        array->SetValue(i, static_cast<int>(std::lround(field->data[static_cast<std::size_t>(i)])));
      impl_->reference_arrays.push_back(array);
    }
}

VtuSeriesWriter::~VtuSeriesWriter() = default;

void VtuSeriesWriter::write_frame(const std::string& path, double time, std::int64_t step,
                                  const std::vector<PointArray>& arrays) {
  vtkNew<vtkUnstructuredGrid> grid;
  grid->SetPoints(impl_->points);
  grid->SetCells(VTK_VERTEX, impl_->cells);
  for (const auto& array : impl_->reference_arrays) grid->GetPointData()->AddArray(array);
  for (const auto& a : arrays) {
    vtkNew<vtkDoubleArray> array;
    array->SetName(a.name.c_str());
    array->SetNumberOfComponents(a.components);
    // Zero copy: VTK only reads the caller's buffer (save = 1: VTK never frees it).
    array->SetArray(const_cast<double*>(a.data), impl_->count * a.components, 1);
    grid->GetPointData()->AddArray(array);
  }
  vtkNew<vtkDoubleArray> time_value;
  time_value->SetName("TimeValue");  // ParaView shows it as the frame time
  time_value->InsertNextValue(time);
  grid->GetFieldData()->AddArray(time_value);
  vtkNew<vtkIntArray> step_value;
  step_value->SetName("step");
  step_value->InsertNextValue(static_cast<int>(step));
  grid->GetFieldData()->AddArray(step_value);

  const std::string temporary = temporary_name_for(path);
  vtkNew<vtkXMLUnstructuredGridWriter> writer;
  writer->SetFileName(temporary.c_str());
  writer->SetInputData(grid);
  writer->SetDataModeToAppended();
  writer->EncodeAppendedDataOff();  // raw binary: smaller and faster than base64
  writer->SetHeaderTypeToUInt64();  // arrays above 4 GiB stay readable
  switch (impl_->compression) {
    case VtuCompression::none:
      writer->SetCompressorTypeToNone();
      break;
    case VtuCompression::zlib: {
      vtkNew<vtkZLibDataCompressor> compressor;
      compressor->SetCompressionLevel(1);  // most of the size gain at a fraction of the time
      writer->SetCompressor(compressor);
      break;
    }
    case VtuCompression::lz4:
      writer->SetCompressorTypeToLZ4();
      break;
  }
  if (writer->Write() != 1) {
    std::error_code ec;
    std::filesystem::remove(temporary, ec);
    throw InputError(path + ": cannot be written (disk full or no permission?)");
  }
  commit_temporary(temporary, path);
}

std::string pvd_text(const std::vector<PvdEntry>& entries) {
  std::ostringstream out;
  out << "<?xml version=\"1.0\"?>\n"
      << "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
      << "  <Collection>\n";
  char buffer[40];
  for (const auto& e : entries) {
    std::snprintf(buffer, sizeof buffer, "%.17g", e.time);
    out << "    <DataSet timestep=\"" << buffer << "\" group=\"\" part=\"0\" file=\"" << e.file << "\"/>\n";
  }
  out << "  </Collection>\n</VTKFile>\n";
  return out.str();
}

}  // namespace mppm::post
