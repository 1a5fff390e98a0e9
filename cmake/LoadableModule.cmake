# recon_add_loadable_module(NAME HOST <static library> DEFINE <macro> SOURCES ... LIBS ...): a
# shared module that HOST opens with dlopen on first use (engine/core/loadable_module.h), for
# libraries that would cost every process their start-up if linked. HOST finds the module at the
# path the build writes it to (the compile definition DEFINE) and is never built without it. The
# module links LIBS and nothing of the project's, so --no-undefined holds, and exports only its
# entry function.
function(recon_add_loadable_module name)
  cmake_parse_arguments(ARG "" "HOST;DEFINE" "SOURCES;LIBS" ${ARGN})
  add_library(${name} MODULE ${ARG_SOURCES})
  target_include_directories(${name} PRIVATE ${RECON_ROOT})
  target_link_libraries(${name} PRIVATE ${ARG_LIBS} recon_warnings)
  set_target_properties(${name} PROPERTIES CXX_VISIBILITY_PRESET hidden
                                           VISIBILITY_INLINES_HIDDEN ON)
  target_link_options(${name} PRIVATE -Wl,--no-undefined)
  target_compile_definitions(${ARG_HOST} PRIVATE ${ARG_DEFINE}="$<TARGET_FILE:${name}>")
  add_dependencies(${ARG_HOST} ${name})
endfunction()
