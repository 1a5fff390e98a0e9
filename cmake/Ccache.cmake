# Use ccache when it is installed: a rebuild after a clean checkout then takes seconds.
find_program(RECON_CCACHE ccache)
if(RECON_CCACHE)
  set(CMAKE_C_COMPILER_LAUNCHER "${RECON_CCACHE}")
  set(CMAKE_CXX_COMPILER_LAUNCHER "${RECON_CCACHE}")
endif()
