# MuJoCo's C library and headers from its official PyPI wheel, which
# scripts/setup unpacks into the build tree (scripts/wheels.txt pins it):
# the imported target mujoco::mujoco. Debian 12's libmujoco-dev (2.2.2) is
# not used. Executables in the build tree find the library through CMake's
# build RPATH; installed ones through $ORIGIN/../lib, where install puts it.
set(CHORE_MUJOCO_DIR "${CMAKE_BINARY_DIR}/_deps/mujoco" CACHE PATH
  "The unpacked MuJoCo wheel (its mujoco/ folder holds libmujoco.so.X.Y.Z and include/)")
# Built by pip (scikit-build-core, pyproject.toml): the same wheel is a build
# requirement, installed where the build's Python finds it.
if(SKBUILD AND NOT EXISTS "${CHORE_MUJOCO_DIR}/mujoco/include/mujoco/mujoco.h")
  execute_process(COMMAND "${Python_EXECUTABLE}" -c
    "import importlib.util, os; print(os.path.dirname(importlib.util.find_spec('mujoco').submodule_search_locations[0]))"
    OUTPUT_VARIABLE CHORE_MUJOCO_DIR OUTPUT_STRIP_TRAILING_WHITESPACE COMMAND_ERROR_IS_FATAL ANY)
endif()
file(GLOB _chore_mujoco_library "${CHORE_MUJOCO_DIR}/mujoco/libmujoco.so.*")
if(NOT _chore_mujoco_library OR NOT EXISTS "${CHORE_MUJOCO_DIR}/mujoco/include/mujoco/mujoco.h")
  message(FATAL_ERROR "No MuJoCo in ${CHORE_MUJOCO_DIR}: scripts/setup fetches and unpacks the wheel of scripts/wheels.txt there")
endif()
list(GET _chore_mujoco_library 0 CHORE_MUJOCO_LIBRARY)
get_filename_component(CHORE_MUJOCO_SONAME "${CHORE_MUJOCO_LIBRARY}" NAME)
add_library(mujoco::mujoco SHARED IMPORTED GLOBAL)
set_target_properties(mujoco::mujoco PROPERTIES
  IMPORTED_LOCATION "${CHORE_MUJOCO_LIBRARY}"
  IMPORTED_SONAME "${CHORE_MUJOCO_SONAME}"
  INTERFACE_INCLUDE_DIRECTORIES "${CHORE_MUJOCO_DIR}/mujoco/include")
