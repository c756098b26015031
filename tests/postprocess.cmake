# Tests of postprocess/ (label unit). test_post_stage and test_post_paraview run the built
# mppm-postprocess on run directories generated at test time (unit/test_post_run_fixture).
set(MPPM_TEST_LIBS mppm_postprocess)
mppm_add_gtest(test_post_metrics unit
  unit/test_post_shear_band.cpp
  unit/test_post_crack.cpp
  unit/test_post_crack_area.cpp
  unit/test_post_crack_angle.cpp
  unit/test_post_pore_pressure.cpp
  unit/test_post_fields.cpp
)
mppm_add_gtest(test_post_stage unit
  unit/test_post_output.cpp
  unit/test_post_bad_input.cpp
  unit/test_post_crack_angle_stage.cpp
  unit/test_post_picture_options.cpp
  unit/test_post_run_fixture.cpp
)
# The 3-D run of the picture tests is made by the built preprocessor and solver
# (unit/post_notched_run_3d.hpp).
add_dependencies(test_post_stage mppm-postprocess mppm-preprocess mppm-solve)
# Needs ParaView (pvbatch) and xvfb-run: fails, never skips, when they are missing.
mppm_add_gtest(test_post_paraview unit
  unit/test_post_pvbatch.cpp
  unit/test_post_view_state.cpp
  unit/test_post_pictures.cpp
  unit/test_post_run_fixture.cpp
)
add_dependencies(test_post_paraview mppm-postprocess mppm-preprocess mppm-solve)
# The crack-arrival table from the solver (in-process runs of a notched bar) to the crack metrics
# and the summary of mppm-postprocess's library call.
set(MPPM_TEST_LIBS mppm_solver mppm_postprocess)
mppm_add_gtest(test_crack_path_table unit unit/test_crack_path_table.cpp)
# 3-D crack metrics from end to end: a small 3-D bar with a pre-crack torn apart in process, its
# crack_area field, summary.json and crack_area.csv.
mppm_add_gtest(test_crack_area_stage unit unit/test_crack_area_stage.cpp)
