// The ParaView series: one VTK XML UnstructuredGrid (.vtu, binary) per snapshot with the points
// as vertex cells at their REFERENCE positions, and results.pvd listing them with their times.
// `displacement` (padded to 3 components in 2-D) lets ParaView's Warp By Vector show the
// deformed body. Every file is written under a temporary name and renamed.
#pragma once
#include <memory>
#include <string>
#include <vector>

#include "common/snapshot_file.hpp"

namespace mppm::post {

// A point array as written: name, components, values (point-major).
struct PointArray {
  std::string name;
  int components = 1;
  const double* data = nullptr;  // not owned; points * components values
};

enum class VtuCompression { none, zlib, lz4 };

class VtuSeriesWriter {
 public:
  // reference: the run's reference.snap (position, volume, region, boundary_id).
  VtuSeriesWriter(const Snapshot& reference, VtuCompression compression);
  ~VtuSeriesWriter();
  VtuSeriesWriter(const VtuSeriesWriter&) = delete;
  VtuSeriesWriter& operator=(const VtuSeriesWriter&) = delete;

  // Writes one frame; arrays beyond the reference ones (volume, region, boundary_id).
  void write_frame(const std::string& path, double time, std::int64_t step, const std::vector<PointArray>& arrays);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

struct PvdEntry {
  double time = 0.0;
  std::string file;  // relative to the .pvd
};

// results.pvd text (VTK Collection).
std::string pvd_text(const std::vector<PvdEntry>& entries);

}  // namespace mppm::post
