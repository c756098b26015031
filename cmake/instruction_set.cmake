# mppm_instruction_set_flags(OUT): the -march flags for MPPM_ARCH (CMakeLists.txt), checked once at
# configure time. "auto" takes x86-64-v4 (AVX-512) or else x86-64-v3 (AVX2, FMA) only if the
# compiler accepts it and this machine's processor has its features, so a build never produces
# binaries that stop with an illegal instruction here; a configure message says what was chosen.
# x86-64-v4 is for its 32 vector registers more than its wider vectors: the force kernel's bond
# loop with damage keeps about 30 values live, and with 16 registers half of them go through the
# stack (the crack-branching base case: 9.20 s against 9.74 s, fastest of 3 interleaved runs).
include(CheckCXXCompilerFlag)
include(CheckCXXSourceRuns)

# The processor features of each level "auto" tries, highest first (names of GCC's
# __builtin_cpu_supports).
set(MPPM_AUTO_LEVELS x86-64-v4 x86-64-v3)
set(MPPM_FEATURES_x86-64-v3 avx2 fma bmi2)
set(MPPM_FEATURES_x86-64-v4 ${MPPM_FEATURES_x86-64-v3} avx512f avx512bw avx512cd avx512dq avx512vl)

# mppm_auto_level(OUT): the highest level of MPPM_AUTO_LEVELS that the compiler accepts and this
# machine's processor runs (asked by a program built without the flag), or "" for none.
function(mppm_auto_level out)
  foreach(level IN LISTS MPPM_AUTO_LEVELS)
    check_cxx_compiler_flag("-march=${level}" MPPM_COMPILER_HAS_MARCH_${level})
    if(NOT MPPM_COMPILER_HAS_MARCH_${level})
      continue()
    endif()
    set(checks ${MPPM_FEATURES_${level}})
    list(TRANSFORM checks REPLACE "(.+)" "__builtin_cpu_supports(\"\\1\")")
    list(JOIN checks " && " condition)
    string(MAKE_C_IDENTIFIER "${level}" id)
    string(TOUPPER "${id}" id)
    check_cxx_source_runs("int main() { __builtin_cpu_init(); return ${condition} ? 0 : 1; }"
                          MPPM_MACHINE_RUNS_${id})
    if(MPPM_MACHINE_RUNS_${id})
      set(${out} "${level}" PARENT_SCOPE)
      return()
    endif()
  endforeach()
  set(${out} "" PARENT_SCOPE)
endfunction()

function(mppm_instruction_set_flags out)
  if(MPPM_ARCH STREQUAL "default" OR MPPM_ARCH STREQUAL "")
    message(STATUS "mppm instruction set: compiler default (MPPM_ARCH=default)")
    set(${out} "" PARENT_SCOPE)
    return()
  endif()
  if(MPPM_ARCH STREQUAL "auto")
    mppm_auto_level(candidate)
    if(NOT candidate)
      list(JOIN MPPM_AUTO_LEVELS " nor " levels)
      message(STATUS "mppm instruction set: compiler default (neither ${levels} is both accepted by "
                     "the compiler and run by this machine's processor)")
      set(${out} "" PARENT_SCOPE)
      return()
    endif()
  else()
    set(candidate "${MPPM_ARCH}")
    check_cxx_compiler_flag("-march=${candidate}" MPPM_COMPILER_HAS_MARCH_${candidate})
    if(NOT MPPM_COMPILER_HAS_MARCH_${candidate})
      message(FATAL_ERROR "MPPM_ARCH=${MPPM_ARCH}: the compiler does not accept -march=${candidate} "
                          "(use auto, native, default or a -march value it knows)")
    endif()
  endif()
  message(STATUS "mppm instruction set: -march=${candidate} (MPPM_ARCH=${MPPM_ARCH})")
  # No fused multiply-adds chosen by the compiler: with them, ties in the geometry (a pre-crack
  # midway between lattice rows) could be decided otherwise than in a build without them, and the
  # force kernel's bits would follow the compiler's inlining. The kernel writes its own
  # (solver/multiply_add.hpp).
  set(${out} "-march=${candidate};-ffp-contract=off" PARENT_SCOPE)
endfunction()
