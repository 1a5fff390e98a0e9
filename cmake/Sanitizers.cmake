# RECON_SANITIZE turns on AddressSanitizer + UndefinedBehaviorSanitizer for every target;
# RECON_SANITIZE_THREAD turns on ThreadSanitizer (the two cannot be combined). scripts/sanitize
# builds and runs both.
if(RECON_SANITIZE AND RECON_SANITIZE_THREAD)
  message(FATAL_ERROR "RECON_SANITIZE (ASan + UBSan) and RECON_SANITIZE_THREAD (TSan) cannot be "
                      "combined in one build: use the presets asan and tsan")
endif()
# Both at -O1 with line tables only (-g1): enough for a report's function names and lines, and
# the sanitizer builds compile in about half the time of -O2 -g, which is what lets .ci/run
# afford them (scripts/sanitize).
if(RECON_SANITIZE)
  # -O1, as ASan's authors advise: unoptimised, the AprilTag detections on whole camera images
  # took over 600 s each under ASan; the asan preset is otherwise Debug, so asserts stay on.
  add_compile_options(-O1 -g1 -fsanitize=address,undefined -fno-omit-frame-pointer
                      -fno-sanitize-recover=undefined)
  add_link_options(-fsanitize=address,undefined)
endif()
if(RECON_SANITIZE_THREAD)
  add_compile_options(-O1 -g1 -fsanitize=thread -fno-omit-frame-pointer)
  add_link_options(-fsanitize=thread)
endif()
