# CTest tests of the real softraster executable (included from Tests/Headless/CMakeLists.txt):
#  headless_errors   bad input gives exit 1 (2 for a bad flag) and ONE stderr line naming the file
#  headless_unicode  non-ASCII --obj/--out paths (the wmain entry point under MinGW/Wine)
#  headless_soak     bench --flight: 10,000 frames, no non-finite depth, memory flat (native Linux)
set(_script ${CMAKE_CURRENT_SOURCE_DIR}/RobustnessCheck.cmake)
set(_exe $<TARGET_FILE:softraster>)
set(_emu "${CMAKE_CROSSCOMPILING_EMULATOR}")
foreach(mode errors unicode)
  add_test(NAME headless_${mode}
           COMMAND ${CMAKE_COMMAND} -DMODE=${mode} "-DEXE=${_exe}" "-DEMULATOR=${_emu}"
                   -DWORK=${CMAKE_CURRENT_BINARY_DIR}/robustness-${mode} -P ${_script})
  # Wine turns Unix arguments into UTF-16 with the locale's charset: make it UTF-8.
  set_tests_properties(headless_${mode} PROPERTIES ENVIRONMENT "LC_ALL=C.UTF-8;WINEDEBUG=-all")
  sr_wine_test(headless_${mode})
endforeach()
if(NOT CMAKE_CROSSCOMPILING)
  # Under ASan freed memory sits in quarantine (RSS grows by design): fewer frames, NaN check only.
  if(SR_SANITIZE)
    set(_frames 2000)
    set(_checkMemory OFF)
  else()
    set(_frames 10000)
    set(_checkMemory ON)
  endif()
  add_test(NAME headless_soak
           COMMAND ${CMAKE_COMMAND} -DMODE=soak "-DEXE=${_exe}" -DFRAMES=${_frames} -DCHECK_MEMORY=${_checkMemory}
                   -DWORK=${CMAKE_CURRENT_BINARY_DIR}/robustness-soak -P ${_script})
  set_tests_properties(headless_soak PROPERTIES TIMEOUT 900)
endif()
