// libFuzzer target: the points-file reader (read_point_cloud, VTK XML PolyData) on arbitrary
// bytes. The file is parsed by our own reader (common/vtk_xml_reader.cpp), instrumented, so
// coverage guides the fuzzer through the XML, the block headers and the validation; VTK is
// used only by write_point_cloud in the round-trip check.
#include <vtkLogger.h>
#include <vtkOutputWindow.h>

#include <cstddef>
#include <cstdint>

#include "tests/fuzz/fuzz_entry_points.hpp"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  // The zlib wrapper reports to an observer and VTK may also print; printing thousands of
  // messages per second would only slow the fuzzer down.
  vtkOutputWindow::GetInstance()->SetDisplayModeToNever();
  vtkLogger::SetStderrVerbosity(vtkLogger::VERBOSITY_OFF);
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = mppm::fuzz::write_temporary_input({reinterpret_cast<const char*>(data), size}, ".vtp");
  mppm::fuzz::feed_point_cloud_file(path);
  return 0;
}
