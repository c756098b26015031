// A strict reader of the VTK XML PolyData subset that carries the material points (POINTS.vtp).
// VTK 9.1's own XML reader crashes or aborts on some corrupted files (tests/fuzz/README.md), so
// the points file is parsed here instead: every size, offset, block header and count is checked
// against the file before anything is allocated or copied, and every problem is an InputError
// naming the file. Supported: format="ascii" and format="appended" with encoding="raw",
// uncompressed or vtkZLibDataCompressor, header_type UInt32/UInt64, either byte order; that
// covers what mppm-preprocess writes and what ParaView writes by default.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

namespace mppm {

struct VtkArray {
  std::string name;
  std::string type;  // VTK type name: "Float64", "Int32", "String", ...
  int components = 1;
  std::int64_t tuples = 0;
  std::vector<double> numbers;       // numeric types (integers exact up to 2^53)
  std::vector<std::string> strings;  // type "String"
  bool is_string() const { return type == "String"; }
};

struct VtkPolyDataArrays {
  std::int64_t point_count = 0;
  std::vector<VtkArray> field_data;
  std::vector<VtkArray> point_data;
  VtkArray points;  // the coordinates, 3 components
  const VtkArray* field(const std::string& name) const;
  const VtkArray* point(const std::string& name) const;
};

// Reads the field data, point data and point coordinates of a one-piece VTK XML PolyData file.
// Cells (Verts, Lines, ...) are skipped: the points file needs none of them.
VtkPolyDataArrays read_vtk_polydata_arrays(const std::string& path);

}  // namespace mppm
