// The points file's own reader (common/vtk_xml_reader.hpp) on what VTK writes: every encoding
// it claims to read gives back exactly the values written (also arrays of many compressed
// blocks, i.e. real file sizes, which the small fuzz seeds do not reach), and the encodings
// it does not read are refused with a message naming the file and what to do.
#include <gtest/gtest.h>
#include <vtkNew.h>
#include <vtkPolyData.h>
#include <vtkXMLPolyDataReader.h>
#include <vtkXMLPolyDataWriter.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "common/input_error.hpp"
#include "common/point_cloud.hpp"
#include "common/vtk_xml_reader.hpp"

namespace mppm {
namespace {

namespace fs = std::filesystem;

std::string scratch() {
  const fs::path dir = fs::path(MPPM_BINARY_DIR) / "test_scratch" / "vtk_xml_reader";
  fs::create_directories(dir);
  return dir.string();
}

// A 2-D cloud of n points with values that differ from point to point (a wrong offset or a
// block put in the wrong place would show), two boundaries and a pre-crack segment.
PointCloud cloud_of(std::size_t n) {
  PointCloud c;
  c.dimension = 2;
  c.spacing = 1e-3;
  c.horizon = 3.015e-3;
  c.thickness = 2e-3;
  c.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    c.x[i] = 1e-3 * static_cast<double>(i % 97) + 1e-7 * std::sin(static_cast<double>(i));
    c.y[i] = 1e-3 * static_cast<double>(i / 97);
    c.volume[i] = 1e-9 * (1.0 + 1e-3 * static_cast<double>(i % 13));
    c.region[i] = i % 50 == 0 ? 1 : 0;
    c.boundary_id[i] = c.region[i] ? 1 : (i % 31 == 0 ? 2 : 0);
    c.normal_y[i] = c.boundary_id[i] == 2 ? 1.0 : 0.0;
  }
  c.boundaries = {BoundaryInfo{"bottom", "velocity", 1e-4, 7, "", 0.0},
                  BoundaryInfo{"top side", "traction", 2e-4, 3, "", 0.0}};
  c.precrack_vertices = {0, 0.02, 0, 0.05, 0.02, 0};
  return c;
}

void expect_same(const PointCloud& a, const PointCloud& b) {
  EXPECT_EQ(a.dimension, b.dimension);
  EXPECT_EQ(a.spacing, b.spacing);
  EXPECT_EQ(a.horizon, b.horizon);
  EXPECT_EQ(a.thickness, b.thickness);
  EXPECT_EQ(a.x, b.x);  // bitwise: binary encodings carry the doubles unchanged
  EXPECT_EQ(a.y, b.y);
  EXPECT_EQ(a.z, b.z);
  EXPECT_EQ(a.volume, b.volume);
  EXPECT_EQ(a.region, b.region);
  EXPECT_EQ(a.boundary_id, b.boundary_id);
  EXPECT_EQ(a.normal_y, b.normal_y);
  EXPECT_EQ(a.precrack_vertices, b.precrack_vertices);
  ASSERT_EQ(a.boundaries.size(), b.boundaries.size());
  for (std::size_t k = 0; k < a.boundaries.size(); ++k) {
    EXPECT_EQ(a.boundaries[k].name, b.boundaries[k].name);
    EXPECT_EQ(a.boundaries[k].type, b.boundaries[k].type);
    EXPECT_EQ(a.boundaries[k].area, b.boundaries[k].area);
    EXPECT_EQ(a.boundaries[k].point_count, b.boundaries[k].point_count);
  }
}

enum class Mode { appended_zlib_uint32, appended_uncompressed, ascii, inline_base64, appended_base64 };

// Rewrites `ours` (written by write_point_cloud) with VTK in another encoding, as ParaView's
// "Save Data" would.
std::string rewrite_with_vtk(const std::string& ours, Mode mode, const std::string& name) {
  vtkNew<vtkXMLPolyDataReader> reader;
  reader->SetFileName(ours.c_str());
  reader->Update();
  vtkNew<vtkXMLPolyDataWriter> writer;
  writer->SetInputData(reader->GetOutput());
  const std::string path = scratch() + "/" + name;
  writer->SetFileName(path.c_str());
  switch (mode) {
    case Mode::appended_zlib_uint32:
      writer->SetDataModeToAppended();
      writer->EncodeAppendedDataOff();
      writer->SetCompressorTypeToZLib();
      writer->SetHeaderTypeToUInt32();
      writer->SetBlockSize(4096);  // many blocks per array
      break;
    case Mode::appended_uncompressed:
      writer->SetDataModeToAppended();
      writer->EncodeAppendedDataOff();
      writer->SetCompressorTypeToNone();
      break;
    case Mode::ascii:
      writer->SetDataModeToAscii();
      break;
    case Mode::inline_base64:
      writer->SetDataModeToBinary();
      break;
    case Mode::appended_base64:
      writer->SetDataModeToAppended();
      writer->EncodeAppendedDataOn();
      break;
  }
  EXPECT_EQ(writer->Write(), 1);
  return path;
}

TEST(VtkXmlReader, ReadsOurFilesOfManyCompressedBlocksBitForBit) {
  // 20,000 points: each coordinate array is 480 KB, 15 blocks of VTK's 32 KiB.
  const PointCloud c = cloud_of(20000);
  const std::string path = scratch() + "/ours.vtp";
  write_point_cloud(c, path);
  expect_same(c, read_point_cloud(path));
}

TEST(VtkXmlReader, ReadsTheOtherEncodingsVtkWrites) {
  const PointCloud c = cloud_of(3000);
  const std::string ours = scratch() + "/source.vtp";
  write_point_cloud(c, ours);
  expect_same(c, read_point_cloud(rewrite_with_vtk(ours, Mode::appended_zlib_uint32, "zlib_uint32.vtp")));
  expect_same(c, read_point_cloud(rewrite_with_vtk(ours, Mode::appended_uncompressed, "uncompressed.vtp")));
  // ascii: VTK prints doubles with enough digits to read back the same values.
  expect_same(c, read_point_cloud(rewrite_with_vtk(ours, Mode::ascii, "ascii.vtp")));
}

TEST(VtkXmlReader, RefusesBase64EncodingsWithAMessageNamingTheFile) {
  const std::string ours = scratch() + "/source64.vtp";
  write_point_cloud(cloud_of(10), ours);
  for (const auto& [mode, name, fragment] :
       {std::tuple{Mode::inline_base64, "inline.vtp", "format 'binary' (inline base64) is not supported"},
        std::tuple{Mode::appended_base64, "appended64.vtp", "encoding 'base64' is not supported"}}) {
    const std::string path = rewrite_with_vtk(ours, mode, name);
    try {
      read_point_cloud(path);
      ADD_FAILURE() << name << " was accepted";
    } catch (const InputError& e) {
      const std::string message = e.what();
      EXPECT_EQ(message.rfind(path + ": ", 0), 0u) << message;
      EXPECT_NE(message.find(fragment), std::string::npos) << message;
    }
  }
}

// The file of cloud_of(5) with its piece claiming `count` points.
std::string with_point_count(const std::string& count) {
  const std::string ours = scratch() + "/count.vtp";
  write_point_cloud(cloud_of(5), ours);
  std::string text;
  {
    std::ifstream in(ours, std::ios::binary);
    text.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  const std::size_t at = text.find("NumberOfPoints=\"5\"");
  EXPECT_NE(at, std::string::npos);
  if (at != std::string::npos) text.replace(at, 18, "NumberOfPoints=\"" + count + "\"");
  const std::string bad = scratch() + "/count_" + count + ".vtp";
  std::ofstream(bad, std::ios::binary) << text;
  return bad;
}

TEST(VtkXmlReader, ArraySizesMustMatchThePointCount) {
  // The piece claims one point more than the arrays hold: refused before any array is used.
  try {
    read_point_cloud(with_point_count("6"));
    FAIL() << "accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("expected 6 values x 8 bytes = 48"), std::string::npos) << e.what();
  }
  // A count of 10^11 points (800 GB for one array of doubles): refused by the same check, before
  // an array of that size is allocated (not std::bad_alloc).
  try {
    read_point_cloud(with_point_count("100000000000"));
    FAIL() << "accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("expected 100000000000 values x 8 bytes"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace mppm
