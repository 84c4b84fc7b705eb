# `cmake --install` (and `make install`): the sdgbehave executable, the
# headers a behavior plugin is compiled against, and the CMake package
# `sdgbehave` whose imported target `sdgbehave::plugin` builds a plugin out
# of the source tree (docs/plugins.md).
#
# A plugin is a MODULE library that sdgbehave dlopens; it links none of the
# sdg_* static libraries: their symbols resolve from the executable, which
# exports them (ENABLE_EXPORTS in app/CMakeLists.txt). So nothing but the
# executable, its image module and headers is installed, and the package
# has no library.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

install(TARGETS sdgbehave RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
# The image module (every format but 8-bit PNG), found at run time beside
# the executable as <prefix>/lib/sdgbehave/sdgbehave_images.so.
install(TARGETS sdgbehave_images LIBRARY DESTINATION lib/sdgbehave)

# The include closure of behavior/plugin_api.h, behavior/interval_behavior.h,
# core/log.h (what the templates in lib/builtin_behaviors/templates use) and
# builtin_behaviors/templates/base_behavior.h, as `g++ -MM -Ilib` lists it; paths
# relative to lib/, installed with that layout below include/sdgbehave/.
# tests/python/check_install.py compares this list with the closure
# (`c++ -MM` of lib/builtin_behaviors/templates/*), so an #include added to one of
# these headers or to a template without updating the list fails that test.
set(SDG_PLUGIN_HEADERS
  behavior/behavior.h
  behavior/event_bus.h
  behavior/interval_behavior.h
  behavior/plugin_api.h
  behavior/registry.h
  behavior/rng.h
  builtin_behaviors/templates/base_behavior.h
  core/diagnostics.h
  core/dropped.h
  core/log.h
  core/payload.h
  core/source_loc.h
  stage/behavior_spec.h
  stage/math_types.h
  stage/prim.h
  stage/prim_types.h
  stage/shared_array.h
  stage/stage.h
  stage/stage_animation.h
  stage/value.h
  stage/xform.h)
set(SDG_INSTALL_INCLUDEDIR ${CMAKE_INSTALL_INCLUDEDIR}/sdgbehave)
foreach(header ${SDG_PLUGIN_HEADERS})
  get_filename_component(dir ${header} DIRECTORY)
  install(FILES ${PROJECT_SOURCE_DIR}/lib/${header} DESTINATION ${SDG_INSTALL_INCLUDEDIR}/${dir})
endforeach()

# The plugin ABI version the installed headers declare, for the package's users.
file(STRINGS ${PROJECT_SOURCE_DIR}/lib/behavior/plugin_api.h SDG_PLUGIN_ABI_LINE
     REGEX "^#define SDG_PLUGIN_ABI_VERSION [0-9]+")
string(REGEX REPLACE ".* ([0-9]+)$" "\\1" SDG_PLUGIN_ABI_VERSION "${SDG_PLUGIN_ABI_LINE}")

# Eigen's static alignment is part of the layout of sdg::Value and of every
# class holding one (sizeof(sdg::Value) is 160 bytes with SSE's 16-byte
# alignment, 192 with AVX's 32): it follows the instruction set the code is
# compiled for. The package pins the value sdgbehave is built with, so a
# plugin built with -march=native still agrees with the executable.
if(NOT DEFINED SDG_EIGEN_STATIC_ALIGN)
  set(probe ${PROJECT_BINARY_DIR}/cmake/eigen_align_probe.cpp)
  file(WRITE ${probe} "#include <Eigen/Core>\nstatic_assert(EIGEN_MAX_STATIC_ALIGN_BYTES == SDG_BYTES);\nint main() {}\n")
  foreach(bytes 16 32 64 0)
    try_compile(aligned ${PROJECT_BINARY_DIR}/cmake/eigen_align_probe ${probe}
                COMPILE_DEFINITIONS -DSDG_BYTES=${bytes} LINK_LIBRARIES Eigen3::Eigen CXX_STANDARD 20)
    if(aligned)
      set(SDG_EIGEN_STATIC_ALIGN ${bytes} CACHE INTERNAL "EIGEN_MAX_STATIC_ALIGN_BYTES of this build")
      break()
    endif()
  endforeach()
  if(NOT DEFINED SDG_EIGEN_STATIC_ALIGN)
    message(FATAL_ERROR "could not find EIGEN_MAX_STATIC_ALIGN_BYTES for the installed plugin package")
  endif()
endif()

set(SDG_INSTALL_CMAKEDIR ${CMAKE_INSTALL_LIBDIR}/cmake/sdgbehave)
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/sdgbehaveConfig.cmake.in
  ${PROJECT_BINARY_DIR}/cmake/sdgbehaveConfig.cmake
  INSTALL_DESTINATION ${SDG_INSTALL_CMAKEDIR}
  PATH_VARS SDG_INSTALL_INCLUDEDIR CMAKE_INSTALL_BINDIR)
# 0.x: a new minor version may change the plugin ABI.
write_basic_package_version_file(${PROJECT_BINARY_DIR}/cmake/sdgbehaveConfigVersion.cmake
  COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/cmake/sdgbehaveConfig.cmake
              ${PROJECT_BINARY_DIR}/cmake/sdgbehaveConfigVersion.cmake
        DESTINATION ${SDG_INSTALL_CMAKEDIR})

# The Python package for the datasets, `sdgbehave.data` (python/, pure
# Python; docs/datasets-python.md), installed where the interpreter sdgbehave
# embeds looks for packages under the prefix: on Debian
# <prefix>/lib/python3.X/dist-packages, elsewhere site-packages. From the
# build tree it imports with PYTHONPATH=<build>/python (a link to python/).
if(NOT DEFINED SDG_PYTHON_INSTALL_DIR)
  execute_process(COMMAND ${Python3_EXECUTABLE} -c
    "import sys; v = sys.version_info; d = any(p.endswith('dist-packages') for p in sys.path); print(f'lib/python{v[0]}.{v[1]}/' + ('dist-packages' if d else 'site-packages'), end='')"
    OUTPUT_VARIABLE SDG_PYTHON_INSTALL_DEFAULT RESULT_VARIABLE python_failed)
  if(python_failed)
    message(FATAL_ERROR "${Python3_EXECUTABLE} could not say where Python packages go; set SDG_PYTHON_INSTALL_DIR")
  endif()
  set(SDG_PYTHON_INSTALL_DIR ${SDG_PYTHON_INSTALL_DEFAULT} CACHE STRING "Where `sdgbehave.data` is installed, relative to the prefix")
endif()
install(DIRECTORY ${PROJECT_SOURCE_DIR}/python/sdgbehave DESTINATION ${SDG_PYTHON_INSTALL_DIR}
        COMPONENT python FILES_MATCHING PATTERN "*.py" PATTERN "__pycache__" EXCLUDE)
file(CREATE_LINK ${PROJECT_SOURCE_DIR}/python ${PROJECT_BINARY_DIR}/python SYMBOLIC)

# The stand-in Isaac asset root `sdgbehave exec` answers get_assets_root_path()
# with (found as <prefix>/share/sdgbehave/scenes/isaac-stand-in), and the
# project's props and textures its layers name relative to themselves.
install(DIRECTORY ${PROJECT_SOURCE_DIR}/scenes/isaac-stand-in ${PROJECT_SOURCE_DIR}/scenes/props
                  ${PROJECT_SOURCE_DIR}/scenes/textures
        DESTINATION ${CMAKE_INSTALL_DATADIR}/sdgbehave/scenes)
