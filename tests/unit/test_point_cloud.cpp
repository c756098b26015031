// POINTS.vtp (common/point_cloud): a written cloud reads back identically; the write is atomic
// (no temporary left, a failed write leaves no file); the reader rejects damaged files with a
// message naming the file and the problem.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "common/input_error.hpp"
#include "common/point_cloud.hpp"

using namespace mppm;
namespace fs = std::filesystem;

namespace {

fs::path scratch(const std::string& name) {
  const fs::path dir = fs::path(MPPM_BINARY_DIR) / "test_output" / "point_cloud";
  fs::create_directories(dir);
  return dir / name;
}

PointCloud sample_cloud() {
  PointCloud cloud;
  cloud.dimension = 2;
  cloud.spacing = 0.5e-3;
  cloud.horizon = 4.05 * 0.5e-3;
  cloud.thickness = 1e-3;
  const std::size_t n = 7;
  cloud.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    cloud.x[i] = 0.25e-3 + 0.5e-3 * static_cast<double>(i) + 1e-17 * static_cast<double>(i);  // not round
    cloud.y[i] = -0.1 * static_cast<double>(i);
    cloud.z[i] = 0.0;
    cloud.volume[i] = 0.25e-9 + static_cast<double>(i) * 1e-15;
    cloud.region[i] = static_cast<std::int32_t>(i % 3 == 2 ? 2 : 0);
    cloud.boundary_id[i] = cloud.region[i] ? cloud.region[i] : static_cast<std::int32_t>(i % 2);
    cloud.normal_x[i] = cloud.boundary_id[i] == 1 ? 0.6 : 0.0;
    cloud.normal_y[i] = cloud.boundary_id[i] == 1 ? -0.8 : 0.0;
    cloud.normal_z[i] = 0.0;
  }
  cloud.boundaries = {{"top", "traction", 1e-4, 2, "box [[0, 0.019999999999999997], [0.1, 0.02]] m", 5e-4},
                      {"left", "velocity", 4e-5, 2, "'left'", 2.025e-3}};
  cloud.precrack_vertices = {0, 0.02, 0, 0.05, 0.02, 0};
  return cloud;
}

void expect_rejected(const std::string& path, const std::string& fragment) {
  try {
    read_point_cloud(path);
    FAIL() << "expected InputError for " << path;
  } catch (const InputError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find(path), std::string::npos) << message;
    EXPECT_NE(message.find(fragment), std::string::npos) << message;
  }
}

}  // namespace

TEST(PointCloudFile, RoundTripIsExact) {
  const PointCloud cloud = sample_cloud();
  const std::string path = scratch("round_trip.vtp").string();
  write_point_cloud(cloud, path);
  const PointCloud back = read_point_cloud(path);
  EXPECT_EQ(back.dimension, cloud.dimension);
  EXPECT_EQ(back.spacing, cloud.spacing);
  EXPECT_EQ(back.horizon, cloud.horizon);
  EXPECT_EQ(back.thickness, cloud.thickness);
  EXPECT_EQ(back.x, cloud.x);  // binary doubles: bitwise
  EXPECT_EQ(back.y, cloud.y);
  EXPECT_EQ(back.z, cloud.z);
  EXPECT_EQ(back.volume, cloud.volume);
  EXPECT_EQ(back.region, cloud.region);
  EXPECT_EQ(back.boundary_id, cloud.boundary_id);
  EXPECT_EQ(back.normal_x, cloud.normal_x);
  EXPECT_EQ(back.normal_y, cloud.normal_y);
  EXPECT_EQ(back.precrack_vertices, cloud.precrack_vertices);
  ASSERT_EQ(back.boundaries.size(), 2u);
  EXPECT_EQ(back.boundaries[1].name, "left");
  EXPECT_EQ(back.boundaries[1].type, "velocity");
  EXPECT_EQ(back.boundaries[0].area, 1e-4);
  EXPECT_EQ(back.boundaries[0].point_count, 2);
  // What each layer was made from (the solver compares it with the scene).
  EXPECT_EQ(back.boundaries[0].selector, cloud.boundaries[0].selector);
  EXPECT_EQ(back.boundaries[1].selector, "'left'");
  EXPECT_EQ(back.boundaries[0].depth, 5e-4);
  EXPECT_EQ(back.boundaries[1].depth, 2.025e-3);
  // Binary appended and compressed, as docs/stages.md promises ParaView.
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  EXPECT_NE(text.str().find("vtkZLibDataCompressor"), std::string::npos);
  EXPECT_NE(text.str().find("<AppendedData encoding=\"raw\">"), std::string::npos);
  for (const auto& entry : fs::directory_iterator(fs::path(path).parent_path()))
    EXPECT_EQ(entry.path().string().find(".tmp"), std::string::npos) << "temporary left: " << entry.path();
}

TEST(PointCloudFile, FailedWriteLeavesNoFile) {
  const std::string path = (scratch("") / "no_such_directory" / "points.vtp").string();
  EXPECT_THROW(write_point_cloud(sample_cloud(), path), InputError);
  EXPECT_FALSE(fs::exists(path));
}

TEST(PointCloudFile, DamagedFilesAreRejectedWithTheFileName) {
  expect_rejected(scratch("missing.vtp").string(), "not found");
  const std::string good = scratch("good.vtp").string();
  write_point_cloud(sample_cloud(), good);
  std::ifstream in(good, std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  {  // truncated in the middle of the binary data
    const std::string path = scratch("truncated.vtp").string();
    std::ofstream(path, std::ios::binary) << bytes.substr(0, bytes.size() * 3 / 4);
    expect_rejected(path, "");
  }
  {  // an array renamed: the reader must notice that `volume` is missing
    std::string renamed = bytes;
    const auto at = renamed.find("Name=\"volume\"");
    ASSERT_NE(at, std::string::npos);
    renamed.replace(at, 13, "Name=\"volumX\"");
    const std::string path = scratch("no_volume.vtp").string();
    std::ofstream(path, std::ios::binary) << renamed;
    expect_rejected(path, "missing point array 'volume'");
  }
  {  // not XML at all
    const std::string path = scratch("garbage.vtp").string();
    std::ofstream(path) << "this is not a points file\n";
    expect_rejected(path, "");
  }
}

TEST(PointCloudFile, InvalidValuesAreRejected) {
  PointCloud cloud = sample_cloud();
  cloud.volume[3] = -1.0;
  const std::string negative = scratch("negative_volume.vtp").string();
  write_point_cloud(cloud, negative);
  expect_rejected(negative, "volume <= 0");
  cloud = sample_cloud();
  cloud.region[1] = 5;  // only 2 boundaries
  cloud.boundary_id[1] = 5;
  const std::string region = scratch("bad_region.vtp").string();
  write_point_cloud(cloud, region);
  expect_rejected(region, "region 5");
  cloud = sample_cloud();
  cloud.x[0] = std::nan("");
  const std::string nan = scratch("nan.vtp").string();
  write_point_cloud(cloud, nan);
  expect_rejected(nan, "non-finite");
}
