# recon_warnings: the warning set every target of ours compiles with.
add_library(recon_warnings INTERFACE)
target_compile_options(recon_warnings INTERFACE
  -Wall -Wextra -Wpedantic -Wshadow -Wnon-virtual-dtor -Wcast-align -Woverloaded-virtual
  -Wno-unused-parameter)
