# mppm_instruction_set_flags(OUT): the -march flags for MPPM_ARCH (CMakeLists.txt), checked once at
# configure time. "auto" takes x86-64-v3 only if the compiler accepts it and a program built with
# it runs on this machine, so a build never produces binaries that stop with an illegal
# instruction here; a configure message says what was chosen and why.
include(CheckCXXCompilerFlag)
include(CheckCXXSourceRuns)

function(mppm_instruction_set_flags out)
  if(MPPM_ARCH STREQUAL "default" OR MPPM_ARCH STREQUAL "")
    message(STATUS "mppm instruction set: compiler default (MPPM_ARCH=default)")
    set(${out} "" PARENT_SCOPE)
    return()
  endif()
  if(MPPM_ARCH STREQUAL "auto")
    set(candidate "x86-64-v3")
  else()
    set(candidate "${MPPM_ARCH}")
  endif()
  check_cxx_compiler_flag("-march=${candidate}" MPPM_COMPILER_HAS_MARCH_${candidate})
  if(NOT MPPM_COMPILER_HAS_MARCH_${candidate})
    if(MPPM_ARCH STREQUAL "auto")
      message(STATUS "mppm instruction set: compiler default (the compiler does not accept -march=${candidate})")
      set(${out} "" PARENT_SCOPE)
      return()
    endif()
    message(FATAL_ERROR "MPPM_ARCH=${MPPM_ARCH}: the compiler does not accept -march=${candidate} "
                        "(use auto, native, default or a -march value it knows)")
  endif()
  if(MPPM_ARCH STREQUAL "auto")
    # The processor must run what the flag allows: ask it (a program built without the flag).
    check_cxx_source_runs([=[
      int main() {
        __builtin_cpu_init();
        return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma") &&
               __builtin_cpu_supports("bmi2") ? 0 : 1;
      }]=] MPPM_MACHINE_RUNS_X86_64_V3)
    if(NOT MPPM_MACHINE_RUNS_X86_64_V3)
      message(STATUS "mppm instruction set: compiler default (this machine has no AVX2/FMA/BMI2)")
      set(${out} "" PARENT_SCOPE)
      return()
    endif()
  endif()
  message(STATUS "mppm instruction set: -march=${candidate} (MPPM_ARCH=${MPPM_ARCH})")
  # No fused multiply-adds outside the force kernel (solver/CMakeLists.txt): with them, ties in
  # the geometry (a pre-crack midway between lattice rows) could be decided otherwise than in a
  # build without them.
  set(${out} "-march=${candidate};-ffp-contract=off" PARENT_SCOPE)
endfunction()
