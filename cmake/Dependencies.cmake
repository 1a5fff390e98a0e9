# Every dependency comes from Debian packages installed by scripts/install-deps.
find_package(PkgConfig REQUIRED)
find_package(Threads REQUIRED)
find_package(nlohmann_json REQUIRED)
find_package(CLI11 REQUIRED)
find_package(Eigen3 3.4 REQUIRED NO_MODULE)
# MuJoCo's exported target lists /usr/include/libqhull_r, so libqhull-dev must be installed.
find_package(mujoco REQUIRED)
pkg_check_modules(CAIRO REQUIRED IMPORTED_TARGET cairo)
# Headless rendering: Mesa's EGL with a desktop-GL (compatibility profile) context.
find_package(OpenGL REQUIRED COMPONENTS OpenGL EGL)
find_package(apriltag REQUIRED)
# Gamepads by their standard mapping (devices/teleop/sdl_gamepad.h): the joystick API only.
find_package(SDL2 REQUIRED)
find_package(OpenCV REQUIRED COMPONENTS core imgproc imgcodecs videoio calib3d)
# Sessions: robomimic-layout HDF5 through the C library (Debian: libhdf5-dev, serial build).
find_package(HDF5 REQUIRED COMPONENTS C)
if(NOT TARGET hdf5::hdf5)
  add_library(hdf5::hdf5 INTERFACE IMPORTED)
  target_include_directories(hdf5::hdf5 INTERFACE ${HDF5_C_INCLUDE_DIRS})
  target_link_libraries(hdf5::hdf5 INTERFACE ${HDF5_C_LIBRARIES})
  target_compile_definitions(hdf5::hdf5 INTERFACE ${HDF5_C_DEFINITIONS})
endif()

# Torch's CMake config prints warnings about optional CUDA/kineto pieces; they are harmless on CPU.
find_package(Torch REQUIRED)

if(RECON_BUILD_TESTS)
  find_package(GTest REQUIRED)
endif()
if(RECON_BUILD_BENCH)
  find_package(benchmark REQUIRED)
endif()
