# Tests of common/: units, scene parsing and validation, file formats.
set(MPPM_TEST_LIBS mppm_common)
mppm_add_gtest(test_common unit
  unit/test_units.cpp
  unit/test_scene.cpp
  unit/test_scene_pore_fluid.cpp
  unit/test_scene_fluid_boundaries.cpp
  unit/test_scene_reference.cpp
  unit/test_snapshot_file.cpp
  unit/test_json_quote.cpp
)
