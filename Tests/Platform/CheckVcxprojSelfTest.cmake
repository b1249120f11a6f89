# Proves CheckVcxproj.cmake can fail: runs it on copies of the project files, first unchanged
# (must pass), then with one mutation each (must fail and name the problem).
#   cmake -DSR_SOURCE_ROOT=<repo> -DSR_SOURCE_LISTS=<dir> -DSR_WORK_DIR=<scratch dir>
#         -DSR_CHECK_SCRIPT=<CheckVcxproj.cmake> -P CheckVcxprojSelfTest.cmake
cmake_minimum_required(VERSION 3.25)

set(module_dirs Math Raster Platform Resources Tests)
set(failures 0)

# Copies SoftRaster.sln, the shared sheets (cmake/vs) and every .vcxproj under the module folders
# into <dir>, same layout.
function(sr_copy_project_files dir)
  file(REMOVE_RECURSE ${dir})
  file(MAKE_DIRECTORY ${dir})
  file(COPY ${SR_SOURCE_ROOT}/SoftRaster.sln DESTINATION ${dir})
  file(COPY ${SR_SOURCE_ROOT}/cmake/vs DESTINATION ${dir}/cmake)
  foreach(module IN LISTS module_dirs)
    file(GLOB_RECURSE projects RELATIVE ${SR_SOURCE_ROOT} ${SR_SOURCE_ROOT}/${module}/*.vcxproj)
    foreach(p IN LISTS projects)
      get_filename_component(sub ${p} DIRECTORY)
      file(COPY ${SR_SOURCE_ROOT}/${p} DESTINATION ${dir}/${sub})
    endforeach()
  endforeach()
endfunction()

# Runs the check on <dir>; sets <rc> and <out> (stdout + stderr).
function(sr_run_check dir rc out)
  execute_process(
    COMMAND ${CMAKE_COMMAND} -DSR_SOURCE_ROOT=${SR_SOURCE_ROOT} -DSR_PROJECT_ROOT=${dir}
            -DSR_SOURCE_LISTS=${SR_SOURCE_LISTS} -P ${SR_CHECK_SCRIPT}
    RESULT_VARIABLE result OUTPUT_VARIABLE o ERROR_VARIABLE e)
  set(${rc} ${result} PARENT_SCOPE)
  set(${out} "${o}${e}" PARENT_SCOPE)
endfunction()

# Replaces the first match of regex in <dir>/<file> (fails the self-test when nothing matches).
function(sr_mutate dir file regex replacement)
  file(READ ${dir}/${file} text)
  string(REGEX MATCH "${regex}" hit "${text}")
  if(hit STREQUAL "")
    message(FATAL_ERROR "self-test setup: '${regex}' not found in ${file}")
  endif()
  string(FIND "${text}" "${hit}" at)
  string(LENGTH "${hit}" len)
  string(SUBSTRING "${text}" 0 ${at} before)
  math(EXPR after_at "${at} + ${len}")
  string(SUBSTRING "${text}" ${after_at} -1 after)
  file(WRITE ${dir}/${file} "${before}${replacement}${after}")
endfunction()

# One case: mutate a fresh copy, expect failure with the expected message.
macro(sr_expect_failure name expected)
  set(dir ${SR_WORK_DIR}/${name})
  sr_copy_project_files(${dir})
  cmake_language(CALL sr_mutate_${name} ${dir})
  sr_run_check(${dir} rc out)
  string(REGEX MATCH "${expected}" found "${out}")
  if(rc EQUAL 0 OR found STREQUAL "")
    message("FAIL  ${name}: expected a failure matching '${expected}', got rc=${rc}:\n${out}")
    math(EXPR failures "${failures} + 1")
  else()
    message("ok    ${name}: the check failed as it should (${found})")
  endif()
endmacro()

# Baseline: an unchanged copy passes.
sr_copy_project_files(${SR_WORK_DIR}/unchanged)
sr_run_check(${SR_WORK_DIR}/unchanged rc out)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "the unchanged project files do not pass the check (fix vcxproj_sync first):\n${out}")
endif()
message("ok    unchanged copy passes")

# A source file removed from a .vcxproj.
function(sr_mutate_removed_source dir)
  sr_mutate(${dir} Math/Math.vcxproj "<ClCompile Include=\"Vec.cpp\" />" "")
endfunction()
sr_expect_failure(removed_source "in CMake target sr_math but not in Math/Math.vcxproj:[^\n]*\n *- Math/Vec.cpp")

# A file in a .vcxproj that the CMake target does not have.
function(sr_mutate_extra_source dir)
  sr_mutate(${dir} Raster/Raster.vcxproj "<ClInclude Include=\"Pipeline.hpp\" />"
            "<ClInclude Include=\"Pipeline.hpp\" />\n    <ClInclude Include=\"Stale.hpp\" />")
endfunction()
sr_expect_failure(extra_source "in Raster/Raster.vcxproj but not in CMake target sr_raster:[^\n]*\n *- Raster/Stale.hpp")

# A project left out of the solution.
function(sr_mutate_not_in_solution dir)
  sr_mutate(${dir} SoftRaster.sln "Project\\([^\n]*App.vcxproj[^\n]*\nEndProject\n" "")
endfunction()
sr_expect_failure(not_in_solution "Platform/App/App.vcxproj is not in SoftRaster.sln")

# The solution names a project file that is gone.
function(sr_mutate_missing_project dir)
  file(REMOVE ${dir}/Tests/Math/MathTests.vcxproj)
endfunction()
sr_expect_failure(missing_project "names project 'MathTests' at Tests/Math/MathTests.vcxproj, which does not exist")

# A setting the team agreed on is changed in the shared sheet.
function(sr_mutate_wrong_standard dir)
  sr_mutate(${dir} cmake/vs/SoftRaster.Compile.props "stdcpp17" "stdcpp14")
endfunction()
sr_expect_failure(wrong_standard "SoftRaster.Compile.props: expected <LanguageStandard>stdcpp17</LanguageStandard> once")

# A project overrides a shared setting itself.
function(sr_mutate_local_override dir)
  sr_mutate(${dir} Platform/App/App.vcxproj "<ConfigurationType>StaticLibrary</ConfigurationType>"
            "<ConfigurationType>StaticLibrary</ConfigurationType>\n    <PlatformToolset>v142</PlatformToolset>")
endfunction()
sr_expect_failure(local_override "App.vcxproj: sets <PlatformToolset> itself")

# A project that does not import the compile settings.
function(sr_mutate_missing_sheet dir)
  sr_mutate(${dir} Math/Math.vcxproj "  <Import Project=\"[^\"]*SoftRaster.Compile.props\" />\n" "")
endfunction()
sr_expect_failure(missing_sheet "Math.vcxproj: must import cmake/vs/SoftRaster.Compile.props exactly once .found 0.")

# The configuration sheet imported after Microsoft.Cpp.props (too late: the toolset is chosen there).
function(sr_mutate_sheet_order dir)
  sr_mutate(${dir} Raster/Raster.vcxproj "  <Import Project=\"[^\"]*SoftRaster.Configuration.props\" />\n" "")
  sr_mutate(${dir} Raster/Raster.vcxproj "  <Import Project=\"\\$\\(VCTargetsPath\\)[^\"]*Microsoft.Cpp.props\" />\n"
            "  <Import Project=\"$(VCTargetsPath)\\Microsoft.Cpp.props\" />\n  <Import Project=\"$(MSBuildThisFileDirectory)..\\cmake\\vs\\SoftRaster.Configuration.props\" />\n")
endfunction()
sr_expect_failure(sheet_order "Raster.vcxproj: imports out of order")

# A sheet path that does not reach the repository's cmake/vs (one ..\\ too few).
function(sr_mutate_wrong_sheet_path dir)
  sr_mutate(${dir} Tests/Math/MathTests.vcxproj "\\)\\.\\.\\\\\\.\\.\\\\cmake\\\\vs\\\\SoftRaster.Compile.props"
            ")..\\cmake\\vs\\SoftRaster.Compile.props")
endfunction()
sr_expect_failure(wrong_sheet_path "MathTests.vcxproj: imports [^ ]*SoftRaster.Compile.props, which is not the shared sheet")

if(failures GREATER 0)
  message(FATAL_ERROR "CheckVcxproj self-test: ${failures} mutation(s) went unnoticed")
endif()
message(STATUS "CheckVcxproj self-test: OK (every mutation was reported)")
