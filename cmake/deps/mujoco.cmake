# MuJoCo 2.2 (libmujoco-dev) and what headless rendering of it needs: EGL and OpenGL
# (libegl-dev, libegl-mesa0, libgl-dev) and libpng (libpng-dev). Optional: defines
#   mrqp_dep::mujoco         when MuJoCo is found (control/sim, the MuJoCo plant)
#   mrqp_dep::mujoco_render  when EGL, OpenGL and libpng are found as well (rendering)
# Without them control/sim, tests/sim and tools/render are not built; the rest of the tree is.
#
# Debian 12's CMake package of MuJoCo (mujocoTargets.cmake) names an include folder that does not
# exist (/usr/include/libqhull_r/), which CMake refuses: the header and the library are found
# directly instead.
#
# -DMRQP_WITH_MUJOCO=OFF builds without it even where it is installed.
include_guard(GLOBAL)
option(MRQP_WITH_MUJOCO "the MuJoCo plant (control/sim) when MuJoCo is found" ON)
if(MRQP_WITH_MUJOCO)
  find_path(MRQP_MUJOCO_INCLUDE_DIR NAMES mujoco/mujoco.h)
  find_library(MRQP_MUJOCO_LIBRARY NAMES mujoco)
endif()
if(MRQP_WITH_MUJOCO AND MRQP_MUJOCO_INCLUDE_DIR AND MRQP_MUJOCO_LIBRARY)
  add_library(mrqp_dep::mujoco INTERFACE IMPORTED GLOBAL)
  target_include_directories(mrqp_dep::mujoco INTERFACE ${MRQP_MUJOCO_INCLUDE_DIR})
  target_link_libraries(mrqp_dep::mujoco INTERFACE ${MRQP_MUJOCO_LIBRARY})
  find_package(OpenGL QUIET COMPONENTS OpenGL EGL)
  find_package(PNG QUIET)
  if(TARGET OpenGL::EGL AND TARGET OpenGL::OpenGL AND TARGET PNG::PNG)
    add_library(mrqp_dep::mujoco_render INTERFACE IMPORTED GLOBAL)
    target_link_libraries(mrqp_dep::mujoco_render INTERFACE mrqp_dep::mujoco OpenGL::EGL OpenGL::OpenGL PNG::PNG)
  else()
    message(STATUS "mrqp: EGL, OpenGL or libpng not found: no headless rendering of the MuJoCo plant")
  endif()
else()
  message(STATUS "mrqp: MuJoCo (libmujoco-dev) not found or MRQP_WITH_MUJOCO=OFF: the MuJoCo plant (control/sim) is not built")
endif()
