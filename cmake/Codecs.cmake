# The glTF loader's decoding libraries come from package managers, never from this repository:
# meshoptimizer (EXT_meshopt_compression), Draco (KHR_draco_mesh_compression) and libwebp
# (EXT_texture_webp, decoding only).
#  - MSVC: vcpkg (manifest mode, see vcpkg.json): the meshoptimizer, draco and libwebp ports.
#  - GCC/Clang native: Debian's libmeshoptimizer-dev, libdraco-dev and libwebp-dev (shared libraries).
#  - MinGW: static libraries of the same Debian versions, built from Debian's source packages by
#    scripts/build-mingw-deps.sh into a cache outside the repository; SR_MINGW_DEPS_PREFIX is the
#    prefix it prints. Its include/ holds these libraries' headers alone (never the host's).
# Result: INTERFACE targets sr::meshopt (meshoptimizer.h), sr::draco (draco/...), sr::webp
# (webp/decode.h). Draco's headers differ between builds (draco/draco_features.h: Debian's has
# DRACO_TRANSCODER_SUPPORTED, the MinGW build not): use its decoder API only.
add_library(sr_meshopt INTERFACE)
add_library(sr::meshopt ALIAS sr_meshopt)
add_library(sr_draco INTERFACE)
add_library(sr::draco ALIAS sr_draco)
add_library(sr_webp INTERFACE)
add_library(sr::webp ALIAS sr_webp)
# EXT_texture_avif: Debian's libavif-dev in the Linux build (SR_HAVE_AVIF=1); the Windows builds
# have none (its AV1 decoders are not built here): AVIF textures use their fallback image there.
add_library(sr_avif INTERFACE)
add_library(sr::avif ALIAS sr_avif)

if(MSVC OR DEFINED VCPKG_TOOLCHAIN)
  find_package(meshoptimizer CONFIG REQUIRED)
  target_link_libraries(sr_meshopt INTERFACE meshoptimizer::meshoptimizer)
  find_package(draco CONFIG REQUIRED)
  target_link_libraries(sr_draco INTERFACE draco::draco)
  find_package(WebP CONFIG REQUIRED)
  target_link_libraries(sr_webp INTERFACE WebP::webp) # decoding, and the encoder the tests make files with
  target_compile_definitions(sr_avif INTERFACE SR_HAVE_AVIF=0)
  return()
endif()

if(MINGW OR (CMAKE_CROSSCOMPILING AND WIN32))
  set(SR_MINGW_DEPS_PREFIX "" CACHE PATH
      "The prefix scripts/build-mingw-deps.sh prints: MinGW static meshoptimizer, Draco and libwebp")
  set(_sr_how "run scripts/build-mingw-deps.sh (it prints a prefix) and configure with -DSR_MINGW_DEPS_PREFIX=<that prefix>")
  if(NOT SR_MINGW_DEPS_PREFIX)
    message(FATAL_ERROR "SR_MINGW_DEPS_PREFIX is not set: ${_sr_how}")
  endif()
  if(NOT EXISTS "${SR_MINGW_DEPS_PREFIX}/.stamp")
    message(FATAL_ERROR "SR_MINGW_DEPS_PREFIX (${SR_MINGW_DEPS_PREFIX}) is no complete build of the MinGW decoders: ${_sr_how}")
  endif()
  # Full paths: the toolchain file confines find_* to the MinGW sysroot, and nothing is searched.
  # name, library file, a header it must have
  foreach(_sr_lib meshopt:libmeshoptimizer.a:meshoptimizer.h draco:libdraco.a:draco/compression/decode.h
                  webp:libwebpdecoder.a:webp/decode.h)
    string(REPLACE ":" ";" _sr_lib "${_sr_lib}")
    list(GET _sr_lib 0 _sr_name)
    list(GET _sr_lib 1 _sr_file)
    list(GET _sr_lib 2 _sr_header)
    foreach(_sr_path lib/${_sr_file} include/${_sr_header})
      if(NOT EXISTS "${SR_MINGW_DEPS_PREFIX}/${_sr_path}")
        message(FATAL_ERROR "${SR_MINGW_DEPS_PREFIX}/${_sr_path} is missing: ${_sr_how}")
      endif()
    endforeach()
    add_library(sr_mingw_${_sr_name} STATIC IMPORTED)
    set_target_properties(sr_mingw_${_sr_name} PROPERTIES IMPORTED_LOCATION "${SR_MINGW_DEPS_PREFIX}/lib/${_sr_file}")
    target_include_directories(sr_${_sr_name} SYSTEM INTERFACE "${SR_MINGW_DEPS_PREFIX}/include")
    target_link_libraries(sr_${_sr_name} INTERFACE sr_mingw_${_sr_name})
  endforeach()
  get_filename_component(_sr_versions "${SR_MINGW_DEPS_PREFIX}" NAME)
  message(STATUS "MinGW decoders (static): ${_sr_versions}")
  target_compile_definitions(sr_avif INTERFACE SR_HAVE_AVIF=0)
  return()
endif()

# Debian's packages: meshoptimizer and Draco install CMake packages; libwebp a pkg-config file,
# so its header and library are looked up directly.
find_package(meshoptimizer CONFIG QUIET)
if(NOT TARGET meshoptimizer::meshoptimizer)
  message(FATAL_ERROR "meshoptimizer not found: install Debian's 'libmeshoptimizer-dev' (scripts/install-deps.sh does)")
endif()
target_link_libraries(sr_meshopt INTERFACE meshoptimizer::meshoptimizer)

find_package(draco CONFIG QUIET)
if(NOT TARGET draco::draco)
  message(FATAL_ERROR "Draco not found: install Debian's 'libdraco-dev' (scripts/install-deps.sh does)")
endif()
target_link_libraries(sr_draco INTERFACE draco::draco)

find_path(SR_WEBP_INCLUDE_DIR webp/decode.h)
find_library(SR_WEBP_LIBRARY webp)
if(NOT SR_WEBP_INCLUDE_DIR OR NOT SR_WEBP_LIBRARY)
  message(FATAL_ERROR "libwebp not found: install Debian's 'libwebp-dev' (scripts/install-deps.sh does)")
endif()
target_include_directories(sr_webp SYSTEM INTERFACE ${SR_WEBP_INCLUDE_DIR})
target_link_libraries(sr_webp INTERFACE ${SR_WEBP_LIBRARY})

find_package(libavif CONFIG QUIET)
if(NOT TARGET avif)
  message(FATAL_ERROR "libavif not found: install Debian's 'libavif-dev' (scripts/install-deps.sh does)")
endif()
target_link_libraries(sr_avif INTERFACE avif)
target_compile_definitions(sr_avif INTERFACE SR_HAVE_AVIF=1)
