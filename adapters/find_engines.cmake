# How each engine's library is found, for the engines adapters/engines.txt marks `custom`: one
# function per adapter source, dropcheck_find_<source>(FOUND), which links the library into
# dropcheck_adapters, defines what the adapter needs and sets FOUND in the caller's scope. A library
# that is not found only drops its adapter, with a message naming its Debian package.

# Bullet: Debian ships a float and a double build; never link both into one binary.
set(DROPCHECK_BULLET_PRECISION "double" CACHE STRING "Bullet build to link: double (bullet-float64) or float")
set_property(CACHE DROPCHECK_BULLET_PRECISION PROPERTY STRINGS double float)
function(dropcheck_find_bullet found)
  if(DROPCHECK_BULLET_PRECISION STREQUAL "double")
    pkg_check_modules(BULLET IMPORTED_TARGET bullet-float64)
  else()
    pkg_check_modules(BULLET IMPORTED_TARGET bullet)
  endif()
  if(BULLET_FOUND)
    target_link_libraries(dropcheck_adapters PRIVATE PkgConfig::BULLET)
    target_compile_definitions(dropcheck_adapters PRIVATE DROPCHECK_BULLET_VERSION="${BULLET_VERSION}")
  endif()
  set(${found} ${BULLET_FOUND} PARENT_SCOPE)
endfunction()

function(dropcheck_find_box2d found)
  find_package(box2d QUIET)
  if(box2d_FOUND)
    target_link_libraries(dropcheck_adapters PRIVATE box2d::box2d)
    target_compile_definitions(dropcheck_adapters PRIVATE DROPCHECK_BOX2D_VERSION="${box2d_VERSION}")
  endif()
  set(${found} ${box2d_FOUND} PARENT_SCOPE)
endfunction()

# MuJoCo: mujocoConfig.cmake does find_dependency(OpenGL), which libmujoco-dev does not pull in.
function(dropcheck_find_mujoco found)
  find_package(mujoco QUIET)
  if(mujoco_FOUND)
    # Debian's target lists /usr/include/libqhull_r/ among its include dirs; drop it if absent.
    get_target_property(_mj_inc mujoco::mujoco INTERFACE_INCLUDE_DIRECTORIES)
    if(_mj_inc)
      list(FILTER _mj_inc EXCLUDE REGEX "libqhull_r")
      set_target_properties(mujoco::mujoco PROPERTIES INTERFACE_INCLUDE_DIRECTORIES "${_mj_inc}")
    endif()
    target_link_libraries(dropcheck_adapters PRIVATE mujoco::mujoco)
  endif()
  set(${found} ${mujoco_FOUND} PARENT_SCOPE)
endfunction()

# Chipmunk2D: Debian's libchipmunk-dev ships neither a CMake package nor a pkg-config file.
function(dropcheck_find_chipmunk found)
  find_path(CHIPMUNK_INCLUDE_DIR chipmunk/chipmunk.h)
  find_library(CHIPMUNK_LIBRARY chipmunk)
  if(CHIPMUNK_INCLUDE_DIR AND CHIPMUNK_LIBRARY)
    target_include_directories(dropcheck_adapters SYSTEM PRIVATE ${CHIPMUNK_INCLUDE_DIR})
    target_link_libraries(dropcheck_adapters PRIVATE ${CHIPMUNK_LIBRARY})
    set(${found} TRUE PARENT_SCOPE)
  else()
    set(${found} FALSE PARENT_SCOPE)
  endif()
endfunction()

# Simbody: its CMake package (Debian's simbody.pc adds -std=c++11, which would override C++20).
# Simbody 3.7's headers do not compile as C++20 (adapters/simbody_world.hpp): the file that
# includes them is a C++17 library of its own.
function(dropcheck_find_simbody found)
  find_package(Simbody CONFIG QUIET)
  if(Simbody_FOUND)
    add_library(dropcheck_simbody_world STATIC simbody_world.cpp)
    target_compile_features(dropcheck_simbody_world PRIVATE cxx_std_17)
    set_target_properties(dropcheck_simbody_world PROPERTIES CXX_STANDARD 17 UNITY_BUILD OFF)
    target_link_libraries(dropcheck_simbody_world PRIVATE ${Simbody_LIBRARIES} dropcheck::warnings)
    target_link_libraries(dropcheck_adapters PRIVATE dropcheck_simbody_world ${Simbody_LIBRARIES})
  endif()
  set(${found} ${Simbody_FOUND} PARENT_SCOPE)
endfunction()

# DART 6.12: its CMake package (target dart; it asks for C++17, which C++20 satisfies).
function(dropcheck_find_dart found)
  find_package(DART 6.12 CONFIG QUIET)
  if(DART_FOUND)
    target_link_libraries(dropcheck_adapters PRIVATE dart)
  endif()
  set(${found} ${DART_FOUND} PARENT_SCOPE)
endfunction()

# Wild Magic 5: Debian's libwildmagic-dev ships neither a CMake package nor a pkg-config file; its
# version is the shared library's (libWm5Physics.so -> libWm5Physics.so.5.17).
function(dropcheck_find_wildmagic found)
  find_path(WILDMAGIC_INCLUDE_DIR Wm5RigidBody.h PATH_SUFFIXES libwildmagic)
  find_library(WILDMAGIC_PHYSICS Wm5Physics)
  find_library(WILDMAGIC_MATHEMATICS Wm5Mathematics)
  find_library(WILDMAGIC_CORE Wm5Core)
  if(WILDMAGIC_INCLUDE_DIR AND WILDMAGIC_PHYSICS AND WILDMAGIC_MATHEMATICS AND WILDMAGIC_CORE)
    get_filename_component(_wm_real "${WILDMAGIC_PHYSICS}" REALPATH)
    string(REGEX MATCH "[0-9]+\\.[0-9]+$" _wm_version "${_wm_real}")
    if(NOT _wm_version)
      set(_wm_version "5")
    endif()
    # SYSTEM: Wild Magic's headers warn under -Wextra (copy constructors of Tuple).
    target_include_directories(dropcheck_adapters SYSTEM PRIVATE ${WILDMAGIC_INCLUDE_DIR})
    target_link_libraries(dropcheck_adapters PRIVATE ${WILDMAGIC_PHYSICS} ${WILDMAGIC_MATHEMATICS}
      ${WILDMAGIC_CORE})
    target_compile_definitions(dropcheck_adapters PRIVATE
      DROPCHECK_WILDMAGIC_VERSION="${_wm_version}")
    set(${found} TRUE PARENT_SCOPE)
  else()
    set(${found} FALSE PARENT_SCOPE)
  endif()
endfunction()
