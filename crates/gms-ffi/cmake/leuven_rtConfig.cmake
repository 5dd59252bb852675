# find_package(leuven_rt) for the C library of leuven-rt (crates/gms-ffi), installed by
# `cargo cinstall` with scripts/c_package.sh, which puts this file in <prefix>/lib/cmake/leuven_rt.
#
# Targets:
#   leuven_rt::leuven_rt         the shared library (libleuven_rt.so, SONAME libleuven_rt.so.0)
#   leuven_rt::leuven_rt_static  the static library (libleuven_rt.a) with the system libraries
#                                a Rust static library needs
# Both carry the include directory of leuven_rt.h. The prefix is found from this file's place,
# so the installed tree can be moved.

get_filename_component(_leuven_rt_prefix "${CMAKE_CURRENT_LIST_DIR}/../../.." ABSOLUTE)
set(_leuven_rt_include "${_leuven_rt_prefix}/include")
set(_leuven_rt_lib "${_leuven_rt_prefix}/lib")

foreach(_leuven_rt_file "${_leuven_rt_include}/leuven_rt.h" "${_leuven_rt_lib}/libleuven_rt.so"
        "${_leuven_rt_lib}/libleuven_rt.a")
  if(NOT EXISTS "${_leuven_rt_file}")
    set(leuven_rt_FOUND FALSE)
    set(leuven_rt_NOT_FOUND_MESSAGE "leuven_rt: ${_leuven_rt_file} is missing")
    return()
  endif()
endforeach()

include(CMakeFindDependencyMacro)
find_dependency(Threads)

if(NOT TARGET leuven_rt::leuven_rt)
  add_library(leuven_rt::leuven_rt SHARED IMPORTED)
  set_target_properties(leuven_rt::leuven_rt PROPERTIES
    IMPORTED_LOCATION "${_leuven_rt_lib}/libleuven_rt.so"
    IMPORTED_SONAME "libleuven_rt.so.0"
    INTERFACE_INCLUDE_DIRECTORIES "${_leuven_rt_include}")
endif()

if(NOT TARGET leuven_rt::leuven_rt_static)
  add_library(leuven_rt::leuven_rt_static STATIC IMPORTED)
  set_target_properties(leuven_rt::leuven_rt_static PROPERTIES
    IMPORTED_LOCATION "${_leuven_rt_lib}/libleuven_rt.a"
    INTERFACE_INCLUDE_DIRECTORIES "${_leuven_rt_include}"
    INTERFACE_LINK_LIBRARIES "Threads::Threads;m;${CMAKE_DL_LIBS}")
endif()

set(leuven_rt_INCLUDE_DIRS "${_leuven_rt_include}")
set(leuven_rt_LIBRARIES leuven_rt::leuven_rt)
unset(_leuven_rt_file)
unset(_leuven_rt_prefix)
unset(_leuven_rt_include)
unset(_leuven_rt_lib)
