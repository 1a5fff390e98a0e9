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

# Torch's CMake config prints warnings about optional CUDA/kineto pieces; they are harmless on CPU.
find_package(Torch REQUIRED)

if(RECON_BUILD_TESTS)
  find_package(GTest REQUIRED)
endif()
if(RECON_BUILD_BENCH)
  find_package(benchmark REQUIRED)
endif()
