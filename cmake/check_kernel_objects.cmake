# Test script (tests/solver.cmake): the force kernel's file, internal_forces.cpp, is compiled
# with other options than the energies' file, internal_energies.cpp (-fno-rounding-math:
# solver/CMakeLists.txt). An inline function that both files emit out of line is one symbol to
# the linker, which keeps one of the two copies for both: the energies would then be computed by
# the kernel's code (or the reverse), depending on the link order. This fails when the two object files
# define a common inline (weak) function other than ones that only copy numbers.
#   cmake -DNM=<nm> -DOBJECTS=<object files joined by |> -P check_kernel_objects.cmake
string(REPLACE "|" ";" objects "${OBJECTS}")
set(kernel_objects ${objects})
list(FILTER kernel_objects INCLUDE REGEX "/internal_(forces|energies)\\.cpp\\.o(bj)?$")
list(LENGTH kernel_objects found)
if(NOT found EQUAL 2)
  message(FATAL_ERROR "expected the object files of internal_forces.cpp and internal_energies.cpp, found: ${kernel_objects}")
endif()

# The weak symbols (nm types W and V) an object file defines, demangled.
function(weak_symbols object out)
  execute_process(COMMAND "${NM}" -C --defined-only "${object}" OUTPUT_VARIABLE listing RESULT_VARIABLE failed)
  if(failed)
    message(FATAL_ERROR "${NM} ${object} failed")
  endif()
  string(REPLACE ";" "\\;" listing "${listing}")
  string(REPLACE "\n" ";" lines "${listing}")
  set(symbols "")
  foreach(line ${lines})
    if(line MATCHES "^[0-9a-fA-F]+ [WV] (.*)$")
      list(APPEND symbols "${CMAKE_MATCH_1}")
    endif()
  endforeach()
  set(${out} "${symbols}" PARENT_SCOPE)
endfunction()

list(GET kernel_objects 0 first)
list(GET kernel_objects 1 second)
weak_symbols("${first}" first_symbols)
weak_symbols("${second}" second_symbols)
set(shared "")
foreach(symbol ${first_symbols})
  # Copies only: unpacking a symmetric tensor, and the exception-handling personality reference.
  if(symbol MATCHES "unpack_symmetric<|^DW\\.ref\\.__gxx_personality")
    continue()
  endif()
  list(FIND second_symbols "${symbol}" index)
  if(NOT index EQUAL -1)
    list(APPEND shared "${symbol}")
  endif()
endforeach()
if(shared)
  string(REPLACE ";" "\n  " shared "${shared}")
  message(FATAL_ERROR "internal_forces.cpp and internal_energies.cpp both define these inline functions out of "
                      "line (always inline them, or write them without Eigen expressions):\n  ${shared}")
endif()
list(LENGTH first_symbols n1)
list(LENGTH second_symbols n2)
message(STATUS "no arithmetic inline function shared (${n1} and ${n2} weak symbols)")
