# Tests of solver/plasticity: the micro-polar Drucker-Prager Perzyna return map.
find_package(OpenMP REQUIRED COMPONENTS CXX)
set(MPPM_TEST_LIBS mppm_plasticity OpenMP::OpenMP_CXX GTest::gmock)
mppm_add_gtest(test_plasticity unit
  ${CMAKE_CURRENT_LIST_DIR}/unit/test_plasticity_cone.cpp
  ${CMAKE_CURRENT_LIST_DIR}/unit/test_plasticity_return_map.cpp
  ${CMAKE_CURRENT_LIST_DIR}/unit/test_plasticity_classical.cpp
  ${CMAKE_CURRENT_LIST_DIR}/unit/test_plasticity_substepping.cpp
  ${CMAKE_CURRENT_LIST_DIR}/unit/test_plasticity_registry.cpp
  ${CMAKE_CURRENT_LIST_DIR}/unit/test_plasticity_three_dimensional.cpp
)
mppm_add_gtest(test_plasticity_verification verification
  ${CMAKE_CURRENT_LIST_DIR}/verification/test_plasticity_biaxial.cpp
)
# Scene -> model: needs the scene parser of common/.
if(TARGET mppm_common)
  set(MPPM_TEST_LIBS mppm_plasticity mppm_common GTest::gmock)
  mppm_add_gtest(test_plasticity_scene unit
    ${CMAKE_CURRENT_LIST_DIR}/unit/test_plasticity_scene.cpp
  )
endif()
