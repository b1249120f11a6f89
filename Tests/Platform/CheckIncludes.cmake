# Checks that a header stays light: cmake -P CheckIncludes.cmake with
#   -DSR_CXX=<compiler>      GCC or Clang (the include tree comes from -H)
#   -DSR_STD=<17|20>         the project's C++ standard
#   -DSR_SOURCE_ROOT=<repo>  include root
#   -DSR_HEADER=<path>       the header, relative to the root (e.g. Raster/Frame/RenderSettings.hpp)
#   -DSR_WORK_DIR=<dir>      scratch folder
# Compiles a .cpp that includes only SR_HEADER and fails (listing the chains) when its include tree
# names the span loops (ScanlineFill.hpp), the draw templates (Pipeline.hpp) or any intrinsics
# header (*intrin.h): the Platform files include Raster/Frame/RenderSettings.hpp, and the span loops
# and the intrinsics belong to the renderer's inside, not to every file that names a setting.
cmake_minimum_required(VERSION 3.25)

foreach(var SR_CXX SR_STD SR_SOURCE_ROOT SR_HEADER SR_WORK_DIR)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "CheckIncludes: -D${var}=... is required")
  endif()
endforeach()

file(MAKE_DIRECTORY ${SR_WORK_DIR})
set(tu ${SR_WORK_DIR}/include_check.cpp)
file(WRITE ${tu} "#include \"${SR_HEADER}\"\n")
execute_process(COMMAND ${SR_CXX} -std=c++${SR_STD} -I${SR_SOURCE_ROOT} -H -fsyntax-only ${tu}
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE tree)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "CheckIncludes: ${SR_HEADER} does not compile on its own:\n${out}${tree}")
endif()

# -H prints one line per included file: dots (the depth), a space, the path.
string(REPLACE "\n" ";" lines "${tree}")
set(chain "")   # chain[d] = the file at depth d + 1 on the current path
set(found "")
set(flagged "") # depth of the last reported file (its subtree is skipped)
set(forbidden "(^|[/\\\\])(ScanlineFill\\.hpp|Pipeline\\.hpp|[A-Za-z0-9_]*intrin\\.h)$")
foreach(line IN LISTS lines)
  if(NOT line MATCHES "^(\\.+) (.+)$")
    continue()
  endif()
  string(LENGTH "${CMAKE_MATCH_1}" depth)
  if(flagged AND depth GREATER flagged)
    continue() # inside a reported file: only the first forbidden file of a chain is named
  endif()
  set(flagged "")
  math(EXPR keep "${depth} - 1")
  list(SUBLIST chain 0 ${keep} chain)
  list(APPEND chain "${CMAKE_MATCH_2}")
  if(CMAKE_MATCH_2 MATCHES "${forbidden}")
    list(JOIN chain " -> " text)
    list(APPEND found "${text}")
    set(flagged ${depth})
  endif()
endforeach()

if(found)
  set(text "")
  foreach(f IN LISTS found)
    string(APPEND text "  * ${f}\n")
  endforeach()
  message("${SR_HEADER} pulls in what it must not:\n${text}")
  message(FATAL_ERROR "CheckIncludes: FAILED")
endif()
message(STATUS "CheckIncludes: OK (${SR_HEADER}: no span loops, draw templates or intrinsics)")
