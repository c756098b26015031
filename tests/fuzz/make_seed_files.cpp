// Writes the binary seeds of the fuzz corpus (small valid .snap and .vtp files and malformed
// variants of them) with the project's own writers, so the seeds follow the formats exactly.
// Usage: fuzz_make_seeds CORPUS_DIR (writes CORPUS_DIR/snapshot/*, CORPUS_DIR/point_cloud/*).
// The expected message of each bad_* seed is listed by hand in tests/fuzz/expected_errors.txt.
#include <vtkNew.h>
#include <vtkPolyData.h>
#include <vtkXMLPolyDataReader.h>
#include <vtkXMLPolyDataWriter.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <stdexcept>
#include <string>

#include "common/point_cloud.hpp"
#include "common/snapshot_file.hpp"

namespace {

std::string read_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void write_bytes(const std::string& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  if (!out) throw std::runtime_error("cannot write " + path);
}

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const auto pos = text.find(from);
  if (pos == std::string::npos) throw std::runtime_error("seed generator: '" + from + "' not found");
  return text.replace(pos, from.size(), to);
}

template <class T>
std::string with_value_at(std::string bytes, std::size_t offset, T value) {
  std::memcpy(bytes.data() + offset, &value, sizeof value);
  return bytes;
}

mppm::Snapshot small_snapshot(int dimension) {
  mppm::Snapshot s;
  s.dimension = dimension;
  s.step = 120;
  s.time = 3.0e-6;
  s.point_count = 3;
  s.fields.push_back({"displacement", dimension, std::vector<double>(3 * dimension, 0.0)});
  for (std::size_t k = 0; k < s.fields[0].data.size(); ++k) s.fields[0].data[k] = 1e-6 * static_cast<double>(k);
  s.fields.push_back({"damage", 1, {0.0, 0.25, 1.0}});
  return s;
}

void snapshot_seeds(const std::string& dir) {
  std::filesystem::create_directories(dir);
  mppm::write_snapshot(small_snapshot(2), dir + "/valid_2d.snap");
  mppm::write_snapshot(small_snapshot(3), dir + "/valid_3d.snap");
  mppm::Snapshot empty = small_snapshot(2);
  empty.fields.clear();
  mppm::write_snapshot(empty, dir + "/valid_no_fields.snap");

  const std::string good = read_bytes(dir + "/valid_2d.snap");
  // Header offsets (snapshot_file.hpp): magic 0, version 8, dimension 12, step 16, time 24,
  // point count 32, field count 40, first field name length 44.
  write_bytes(dir + "/bad_empty.snap", "");
  write_bytes(dir + "/bad_truncated_header.snap", good.substr(0, 20));
  write_bytes(dir + "/bad_truncated_data.snap", good.substr(0, good.size() / 2));
  write_bytes(dir + "/bad_no_end_marker.snap", good.substr(0, good.size() - 8));
  write_bytes(dir + "/bad_magic.snap", replaced(good, "MPPMSNAP", "MPPMSNAQ"));
  write_bytes(dir + "/bad_version.snap", with_value_at<std::uint32_t>(good, 8, 7));
  write_bytes(dir + "/bad_dimension.snap", with_value_at<std::uint32_t>(good, 12, 5));
  write_bytes(dir + "/bad_point_count_huge.snap", with_value_at<std::uint64_t>(good, 32, ~0ull / 2));
  write_bytes(dir + "/bad_field_count_huge.snap", with_value_at<std::uint32_t>(good, 40, 4000000000u));
  write_bytes(dir + "/bad_field_name_empty.snap", with_value_at<std::uint32_t>(good, 44, 0));
  write_bytes(dir + "/bad_components_zero.snap", with_value_at<std::uint32_t>(good, 44 + 4 + 12, 0));
  std::string flipped = good;
  flipped[70] ^= 0x10;  // inside the displacement values: only the checksum can tell
  write_bytes(dir + "/bad_checksum.snap", flipped);
  write_bytes(dir + "/bad_trailing_bytes.snap", good + "extra");
  write_bytes(dir + "/bad_end_marker.snap", replaced(good, "MPPMEND!", "MPPMEND?"));
}

mppm::PointCloud small_cloud(int dimension) {
  mppm::PointCloud c;
  c.dimension = dimension;
  c.spacing = 1e-3;
  c.horizon = 3.015e-3;
  c.thickness = dimension == 2 ? 1e-3 : 1.0;
  c.resize(4);
  for (std::size_t i = 0; i < 4; ++i) {
    c.x[i] = 1e-3 * static_cast<double>(i % 2);
    c.y[i] = 1e-3 * static_cast<double>(i / 2);
    c.z[i] = 0.0;
    c.volume[i] = dimension == 2 ? 1e-9 : 1e-9;
  }
  c.region = {0, 0, 1, 0};
  c.boundary_id = {0, 2, 1, 0};
  c.normal_y[1] = -1.0;
  c.boundaries = {{"top", "velocity", 1e-6, 1}, {"bottom", "traction", 1e-6, 1}};
  c.precrack_vertices = {0.0, 0.5e-3, 0.0, 0.5e-3, 0.5e-3, 0.0};
  if (dimension == 3) c.precrack_vertices.insert(c.precrack_vertices.end(), {0.0, 0.0, 1e-3});
  return c;
}

void point_cloud_seeds(const std::string& dir) {
  std::filesystem::create_directories(dir);
  mppm::write_point_cloud(small_cloud(2), dir + "/valid_2d.vtp");
  mppm::write_point_cloud(small_cloud(3), dir + "/valid_3d.vtp");
  // The same file in ASCII: VTK reads both, and text gives the fuzzer numbers to mutate.
  vtkNew<vtkXMLPolyDataReader> reader;
  reader->SetFileName((dir + "/valid_2d.vtp").c_str());
  reader->Update();
  vtkNew<vtkXMLPolyDataWriter> writer;
  writer->SetInputData(reader->GetOutput());
  writer->SetDataModeToAscii();
  writer->SetFileName((dir + "/valid_2d_ascii.vtp").c_str());
  if (writer->Write() != 1) throw std::runtime_error("cannot write the ASCII seed");

  const std::string good = read_bytes(dir + "/valid_2d.vtp");
  const std::string ascii = read_bytes(dir + "/valid_2d_ascii.vtp");
  write_bytes(dir + "/bad_empty.vtp", "");
  write_bytes(dir + "/bad_not_xml.vtp", "mppm points, but not VTK XML\n");
  write_bytes(dir + "/bad_truncated.vtp", good.substr(0, good.size() * 2 / 3));
  write_bytes(dir + "/bad_unstructured_grid.vtp", replaced(ascii, "type=\"PolyData\"", "type=\"UnstructuredGrid\""));
  write_bytes(dir + "/bad_missing_volume.vtp", replaced(ascii, "Name=\"volume\"", "Name=\"volumes\""));
  // VTK reads NumberOfPoints values and ignores the rest: a seed, neither valid_ nor bad_.
  write_bytes(dir + "/lenient_extra_values.vtp", replaced(ascii, "NumberOfPoints=\"4\"", "NumberOfPoints=\"3\""));
  write_bytes(dir + "/bad_missing_dimension.vtp", replaced(ascii, "Name=\"dimension\"", "Name=\"dimensions\""));
  write_bytes(dir + "/bad_not_closed.vtp", ascii.substr(0, ascii.find("</PointData>")));
  // Well-formed VTK whose values break the points-file contract (read_point_cloud's checks).
  write_bytes(dir + "/bad_negative_volume.vtp", replaced(ascii, "1e-9 1e-9 1e-9 1e-9", "1e-9 -1e-9 1e-9 1e-9"));
  write_bytes(dir + "/bad_zero_volume.vtp", replaced(ascii, "1e-9 1e-9 1e-9 1e-9", "1e-9 1e-9 0 1e-9"));
  write_bytes(dir + "/bad_nan_coordinate.vtp", replaced(ascii, "0 0.001 0 0.001 0.001 0", "0 nan 0 0.001 0.001 0"));
  write_bytes(dir + "/bad_z_in_2d.vtp", replaced(ascii, "0 0 0 0.001 0 0", "0 0 0.5 0.001 0 0"));
  write_bytes(dir + "/bad_region_out_of_range.vtp", replaced(ascii, "0 0 1 0\n", "0 0 7 0\n"));
  write_bytes(dir + "/bad_layer_boundary_id.vtp", replaced(ascii, "0 2 1 0\n", "0 2 2 0\n"));
  write_bytes(dir + "/bad_fractional_region.vtp", replaced(ascii, "0 0 1 0\n", "0 0 0.5 0\n"));
  write_bytes(dir + "/bad_dimension_4.vtp",
              replaced(ascii, "RangeMax=\"2\">\n        2\n", "RangeMax=\"2\">\n        4\n"));
  write_bytes(dir + "/bad_spacing_negative.vtp",
              replaced(ascii, "RangeMax=\"0.001\">\n        0.001", "RangeMax=\"0.001\">\n        -0.001"));
  write_bytes(dir + "/bad_boundary_type.vtp",
              replaced(ascii, "118 101 108 111 99 105 116 121 0", "118 101 108 111 99 105 116 120 0"));
  write_bytes(dir + "/bad_boundary_count.vtp",
              replaced(ascii, "RangeMax=\"2\">\n        2\n      </DataArray>\n      <Array",
                       "RangeMax=\"2\">\n        3\n      </DataArray>\n      <Array"));
  write_bytes(dir + "/bad_precrack_odd.vtp",
              replaced(replaced(ascii, "NumberOfTuples=\"2\" format=\"ascii\" RangeMin=\"0.0005\"",
                                "NumberOfTuples=\"3\" format=\"ascii\" RangeMin=\"0.0005\""),
                       "0 0.0005 0 0.0005 0.0005 0\n", "0 0.0005 0 0.0005 0.0005 0 1 1 0\n"));
  std::cout << "wrote the seeds; the ASCII valid_2d_ascii.vtp is the base of the hand-edited bad_* variants\n";
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: fuzz_make_seeds CORPUS_DIR\n";
    return 2;
  }
  try {
    snapshot_seeds(std::string(argv[1]) + "/snapshot");
    point_cloud_seeds(std::string(argv[1]) + "/point_cloud");
  } catch (const std::exception& e) {
    std::cerr << "fuzz_make_seeds: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
