// libFuzzer target: the points-file reader (read_point_cloud, VTK XML PolyData) on arbitrary
// bytes. VTK itself is not instrumented, so coverage guides only through our validation.
#include <vtkLogger.h>
#include <vtkOutputWindow.h>

#include <cstddef>
#include <cstdint>

#include "tests/fuzz/fuzz_entry_points.hpp"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  // VTK reports parse errors to observers (read_point_cloud collects them) and also prints
  // them; printing thousands of them per second would only slow the fuzzer down.
  vtkOutputWindow::GetInstance()->SetDisplayModeToNever();
  vtkLogger::SetStderrVerbosity(vtkLogger::VERBOSITY_OFF);
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = mppm::fuzz::write_temporary_input({reinterpret_cast<const char*>(data), size}, ".vtp");
  mppm::fuzz::feed_point_cloud_file(path);
  return 0;
}
