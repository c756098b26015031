# Tests of the preprocessor: lattice and inside test, boundary layers, pre-cracks,
# the points file, the command line (bad input -> exit code 2) and an independent read-back
# of POINTS.vtp with meshio's VTK XML decoder.
set(MPPM_TEST_LIBS mppm_preprocess mppm_common OpenMP::OpenMP_CXX)
mppm_add_gtest(test_preprocess unit
  ${CMAKE_CURRENT_LIST_DIR}/unit/test_preprocess_lattice.cpp
  ${CMAKE_CURRENT_LIST_DIR}/unit/test_preprocess_layers.cpp
  ${CMAKE_CURRENT_LIST_DIR}/unit/test_preprocess_fluid_layers.cpp
  ${CMAKE_CURRENT_LIST_DIR}/unit/test_preprocess_precrack.cpp
  ${CMAKE_CURRENT_LIST_DIR}/unit/test_preprocess_boundary.cpp
  ${CMAKE_CURRENT_LIST_DIR}/unit/test_preprocess_site_order.cpp
)
target_include_directories(test_preprocess PRIVATE ${CMAKE_CURRENT_LIST_DIR}/unit)

set(MPPM_TEST_LIBS mppm_common)
mppm_add_gtest(test_point_cloud unit ${CMAKE_CURRENT_LIST_DIR}/unit/test_point_cloud.cpp)

set(MPPM_TEST_LIBS)
mppm_add_gtest(test_preprocess_cli unit ${CMAKE_CURRENT_LIST_DIR}/unit/test_preprocess_cli.cpp)
add_dependencies(test_preprocess_cli mppm-preprocess)

# meshio read-back: the executable writes the crack-branching plate, the script decodes it
# without VTK and checks arrays and values against the scene.
set(mppm_pre_meshio_file ${CMAKE_BINARY_DIR}/test_output/preprocess_meshio/plate.vtp)
file(MAKE_DIRECTORY ${CMAKE_BINARY_DIR}/test_output/preprocess_meshio)
add_test(NAME preprocess_meshio_write
  COMMAND $<TARGET_FILE:mppm-preprocess> ${PROJECT_SOURCE_DIR}/tests/data/scenes/pre_branching_plate.yaml
          -o ${mppm_pre_meshio_file} --quiet)
set_tests_properties(preprocess_meshio_write PROPERTIES LABELS unit FIXTURES_SETUP preprocess_meshio_points)
add_test(NAME preprocess_meshio_read_back
  COMMAND /usr/bin/python3 ${PROJECT_SOURCE_DIR}/tests/tools/check_points_meshio.py ${mppm_pre_meshio_file})
set_tests_properties(preprocess_meshio_read_back PROPERTIES LABELS unit FIXTURES_REQUIRED preprocess_meshio_points)
