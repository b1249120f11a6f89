# Toolchain: cross-compile for x86_64 Windows with Debian's MinGW-w64 (posix threads flavour).
# ctest runs the resulting .exe files through Wine (CMAKE_CROSSCOMPILING_EMULATOR).
set(CMAKE_SYSTEM_NAME Windows)
set(CMAKE_SYSTEM_PROCESSOR x86_64)

set(SR_MINGW_PREFIX x86_64-w64-mingw32)
set(CMAKE_C_COMPILER   ${SR_MINGW_PREFIX}-gcc-posix)
set(CMAKE_CXX_COMPILER ${SR_MINGW_PREFIX}-g++-posix)
set(CMAKE_RC_COMPILER  ${SR_MINGW_PREFIX}-windres)

# Search only the MinGW sysroot for libraries and headers: never the host's /usr/include.
set(CMAKE_FIND_ROOT_PATH /usr/${SR_MINGW_PREFIX})
set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_PACKAGE ONLY)

find_program(SR_WINE NAMES wine wine64 REQUIRED)
set(CMAKE_CROSSCOMPILING_EMULATOR ${SR_WINE})
