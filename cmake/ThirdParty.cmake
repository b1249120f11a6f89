# Third-party headers come from package managers, never from this repository.
#  - MSVC: vcpkg (manifest mode, see vcpkg.json): Catch2 3.x, stb, tinyobjloader, nlohmann-json.
#  - GCC (native and MinGW): Debian's catch2 (2.x), libstb-dev, libtinyobjloader-dev,
#    nlohmann-json3-dev (the JSON of glTF files; header-only). The MinGW
#    build must not see the host's /usr/include, so the few header folders we use are copied at
#    configure time into <build>/pkg-include, a folder that holds only them.
# Result: INTERFACE targets sr::catch2 (headers; SR_CATCH2_V3 defined for 3.x), sr::stb,
# sr::tinyobjloader, sr::json.
add_library(sr_catch2 INTERFACE)
add_library(sr::catch2 ALIAS sr_catch2)
add_library(sr_stb INTERFACE)
add_library(sr::stb ALIAS sr_stb)
add_library(sr_tinyobjloader INTERFACE)
add_library(sr::tinyobjloader ALIAS sr_tinyobjloader)
add_library(sr_json INTERFACE)
add_library(sr::json ALIAS sr_json)

if(MSVC OR DEFINED VCPKG_TOOLCHAIN)
  if(SR_BUILD_TESTS)
    find_package(Catch2 3 CONFIG REQUIRED)
    target_link_libraries(sr_catch2 INTERFACE Catch2::Catch2WithMain)
    target_compile_definitions(sr_catch2 INTERFACE SR_CATCH2_V3=1)
  endif()
  find_path(SR_STB_DIR stb_image.h REQUIRED)
  target_include_directories(sr_stb SYSTEM INTERFACE ${SR_STB_DIR})
  find_package(tinyobjloader CONFIG REQUIRED)
  target_link_libraries(sr_tinyobjloader INTERFACE tinyobjloader::tinyobjloader)
  find_package(nlohmann_json CONFIG REQUIRED)
  target_link_libraries(sr_json INTERFACE nlohmann_json::nlohmann_json)
  return()
endif()

set(SR_PKG_INCLUDE ${CMAKE_BINARY_DIR}/pkg-include)
set(SR_HOST_INCLUDE /usr/include CACHE PATH "Where Debian's -dev packages put their headers")

# Copies one header file or folder from the host's include dir into SR_PKG_INCLUDE.
function(sr_import_header what package)
  set(src ${SR_HOST_INCLUDE}/${what})
  if(NOT EXISTS ${src})
    message(FATAL_ERROR "${src} not found: install Debian's '${package}' (scripts/install-deps.sh does)")
  endif()
  get_filename_component(dest_parent ${SR_PKG_INCLUDE}/${what} DIRECTORY)
  file(COPY ${src} DESTINATION ${dest_parent})
endfunction()

if(SR_BUILD_TESTS)
  sr_import_header(catch2 catch2)
  target_include_directories(sr_catch2 SYSTEM INTERFACE ${SR_PKG_INCLUDE})
endif()
sr_import_header(stb/stb_image.h libstb-dev)
sr_import_header(stb/stb_image_write.h libstb-dev)
target_include_directories(sr_stb SYSTEM INTERFACE ${SR_PKG_INCLUDE}/stb)
sr_import_header(tiny_obj_loader.h libtinyobjloader-dev)
target_include_directories(sr_tinyobjloader SYSTEM INTERFACE ${SR_PKG_INCLUDE})
sr_import_header(nlohmann nlohmann-json3-dev)
target_include_directories(sr_json SYSTEM INTERFACE ${SR_PKG_INCLUDE})
