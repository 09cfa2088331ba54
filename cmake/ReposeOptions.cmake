# Compiler options applied to repose's own targets (never global flags).
add_library(repose_options INTERFACE)
target_compile_options(repose_options INTERFACE
  -Wall -Wextra -Wpedantic
  # Bit-reproducible floating point: no fused multiply-add contraction, no fast-math.
  -ffp-contract=off
  $<$<BOOL:${REPOSE_WARNINGS_AS_ERRORS}>:-Werror>)
if(REPOSE_CHECKED_STL)
  target_compile_definitions(repose_options INTERFACE _GLIBCXX_ASSERTIONS)
endif()
if(REPOSE_SANITIZE)
  target_compile_options(repose_options INTERFACE
    -fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer
    # -O1 keeps the sanitized suite (Eigen-heavy physics) fast enough for CI; asserts stay on (no NDEBUG).
    -O1)
  target_link_options(repose_options INTERFACE -fsanitize=address,undefined -fno-sanitize-recover=all)
endif()
