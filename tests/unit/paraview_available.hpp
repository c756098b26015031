// Whether the ParaView tests can run: pvbatch and xvfb-run on PATH. An assertion result, not
// ASSERT_* in a helper: those would return from the helper only, and the test would go on
// without ParaView. The tests fail (not skip) without them: `make deps` installs both.
#pragma once
#include <gtest/gtest.h>

#include "postprocess/external_tools.hpp"

namespace mppm::post::testing {

inline ::testing::AssertionResult paraview_installed() {
  if (!mppm::post::find_program("pvbatch"))
    return ::testing::AssertionFailure() << "pvbatch not found: install the Debian package paraview (make deps does)";
  if (!mppm::post::find_program("xvfb-run"))
    return ::testing::AssertionFailure()
           << "xvfb-run not found: install the Debian packages xvfb and xauth (make deps does)";
  return ::testing::AssertionSuccess();
}

}  // namespace mppm::post::testing
