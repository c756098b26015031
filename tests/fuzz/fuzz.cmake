# libFuzzer targets for the untrusted-input readers of common/: fuzz_scene,
# fuzz_quantity, fuzz_snapshot, fuzz_point_cloud. Built only with -DMPPM_FUZZ=ON and clang;
# `make -C workflows fuzz` configures build-fuzz that way and runs them (README.md here).
option(MPPM_FUZZ "Build the libFuzzer targets (needs clang and libclang-rt-14-dev)" OFF)

if(MPPM_FUZZ)
  if(NOT CMAKE_CXX_COMPILER_ID MATCHES "Clang")
    message(FATAL_ERROR "MPPM_FUZZ=ON needs clang (libFuzzer): configure with "
                        "-DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++")
  endif()
  # Address + undefined-behaviour sanitizers, so that a memory error or UB is a crash the
  # fuzzer reports instead of a silent wrong result.
  set(mppm_fuzz_sanitizers -fsanitize=address,undefined -fno-sanitize-recover=undefined
                           -fno-omit-frame-pointer -g)

  # common/ again, with coverage instrumentation so that libFuzzer is guided through it.
  # The sources and usage requirements are taken from mppm_common, so the two stay in step.
  get_target_property(mppm_fuzz_common_sources mppm_common SOURCES)
  get_target_property(mppm_fuzz_common_dir mppm_common SOURCE_DIR)
  set(mppm_fuzz_sources "")
  foreach(source ${mppm_fuzz_common_sources})
    if(NOT IS_ABSOLUTE ${source})
      set(source ${mppm_fuzz_common_dir}/${source})
    endif()
    list(APPEND mppm_fuzz_sources ${source})
  endforeach()
  get_target_property(mppm_fuzz_common_libs mppm_common LINK_LIBRARIES)
  get_target_property(mppm_fuzz_common_defs mppm_common COMPILE_DEFINITIONS)
  add_library(mppm_common_fuzz STATIC ${mppm_fuzz_sources})
  target_include_directories(mppm_common_fuzz PUBLIC ${PROJECT_SOURCE_DIR})
  target_link_libraries(mppm_common_fuzz PUBLIC ${mppm_fuzz_common_libs} VTK::CommonCore)
  if(mppm_fuzz_common_defs)
    target_compile_definitions(mppm_common_fuzz PUBLIC ${mppm_fuzz_common_defs})
  endif()
  target_compile_options(mppm_common_fuzz PRIVATE -fsanitize=fuzzer-no-link ${mppm_fuzz_sanitizers})

  foreach(target scene quantity snapshot point_cloud)
    add_executable(fuzz_${target}
      ${PROJECT_SOURCE_DIR}/tests/fuzz/fuzz_${target}.cpp
      ${PROJECT_SOURCE_DIR}/tests/fuzz/fuzz_entry_points.cpp)
    target_link_libraries(fuzz_${target} PRIVATE mppm_common_fuzz mppm_warnings)
    target_compile_options(fuzz_${target} PRIVATE -fsanitize=fuzzer ${mppm_fuzz_sanitizers})
    target_link_options(fuzz_${target} PRIVATE -fsanitize=fuzzer ${mppm_fuzz_sanitizers})
  endforeach()
  add_custom_target(fuzzers DEPENDS fuzz_scene fuzz_quantity fuzz_snapshot fuzz_point_cloud)
endif()

if(MPPM_FUZZ)
  # Regenerates the binary seeds (see make_seed_files.cpp); not part of any run.
  add_executable(fuzz_make_seeds ${PROJECT_SOURCE_DIR}/tests/fuzz/make_seed_files.cpp)
  target_link_libraries(fuzz_make_seeds PRIVATE mppm_common mppm_warnings VTK::CommonCore VTK::IOXML)
endif()
