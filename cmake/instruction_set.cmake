# mppm_instruction_set_flags(OUT): the -march flags for MPPM_ARCH (CMakeLists.txt), checked once at
# configure time. "auto" takes x86-64-v4 (AVX-512) or else x86-64-v3 (AVX2, FMA) only if the
# compiler accepts it and this machine's processor has its features, so a build never produces
# binaries that stop with an illegal instruction here; a configure message says what was chosen.
# x86-64-v4 is for its 32 vector registers more than its wider vectors: the force kernel's bond
# loop with damage keeps about 30 values live, and with 16 registers half of them go through the
# stack (the crack-branching base case: 9.20 s against 9.74 s, fastest of 3 interleaved runs).
include(CheckCXXCompilerFlag)
include(CheckCXXSourceRuns)

function(mppm_instruction_set_flags out)
  if(MPPM_ARCH STREQUAL "default" OR MPPM_ARCH STREQUAL "")
    message(STATUS "mppm instruction set: compiler default (MPPM_ARCH=default)")
    set(${out} "" PARENT_SCOPE)
    return()
  endif()
  if(MPPM_ARCH STREQUAL "auto")
    # The processor must run what the flag allows: ask it (programs built without the flag).
    check_cxx_source_runs([=[
      int main() {
        __builtin_cpu_init();
        return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma") &&
               __builtin_cpu_supports("bmi2") ? 0 : 1;
      }]=] MPPM_MACHINE_RUNS_X86_64_V3)
    check_cxx_source_runs([=[
      int main() {
        __builtin_cpu_init();
        return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma") &&
               __builtin_cpu_supports("bmi2") && __builtin_cpu_supports("avx512f") &&
               __builtin_cpu_supports("avx512bw") && __builtin_cpu_supports("avx512cd") &&
               __builtin_cpu_supports("avx512dq") && __builtin_cpu_supports("avx512vl") ? 0 : 1;
      }]=] MPPM_MACHINE_RUNS_X86_64_V4)
    check_cxx_compiler_flag("-march=x86-64-v4" MPPM_COMPILER_HAS_MARCH_x86-64-v4)
    check_cxx_compiler_flag("-march=x86-64-v3" MPPM_COMPILER_HAS_MARCH_x86-64-v3)
    if(MPPM_MACHINE_RUNS_X86_64_V4 AND MPPM_COMPILER_HAS_MARCH_x86-64-v4)
      set(candidate "x86-64-v4")
    elseif(MPPM_MACHINE_RUNS_X86_64_V3 AND MPPM_COMPILER_HAS_MARCH_x86-64-v3)
      set(candidate "x86-64-v3")
    elseif(NOT MPPM_COMPILER_HAS_MARCH_x86-64-v3)
      message(STATUS "mppm instruction set: compiler default (the compiler does not accept -march=x86-64-v3)")
      set(${out} "" PARENT_SCOPE)
      return()
    else()
      message(STATUS "mppm instruction set: compiler default (this machine has no AVX2/FMA/BMI2)")
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
  # No fused multiply-adds outside the force kernel (solver/CMakeLists.txt): with them, ties in
  # the geometry (a pre-crack midway between lattice rows) could be decided otherwise than in a
  # build without them.
  set(${out} "-march=${candidate};-ffp-contract=off" PARENT_SCOPE)
endfunction()
