# KINRAY_SANITIZE: every target of the build (libraries, program, tests) with AddressSanitizer and
# UndefinedBehaviorSanitizer. Any undefined behaviour aborts (no recovery), so a finding fails the
# test that reached it instead of scrolling past as a warning. -O1 (after the build type's -O3,
# so it wins) compiles about twice as fast as -O3 under ASan and keeps the reports' stacks
# readable, with frame pointers; -g1 (line tables only) gives those stacks their files and lines
# and compiles about a seventh faster than full debug information. Debian's Embree, TBB, assimp and OSMesa are not instrumented: ASan still
# checks every access kinray's own code makes to the memory they hand out.
#
# KINRAY_FUZZ (clang only): the libraries get libFuzzer's coverage instrumentation
# (-fsanitize=fuzzer-no-link) on top of ASan + UBSan, so that tests/fuzz's harnesses can steer into
# kinray's own parsers.
if(KINRAY_SANITIZE OR KINRAY_FUZZ)
  set(KINRAY_SANITIZER_FLAGS -fsanitize=address,undefined -fno-sanitize-recover=undefined
      -fno-omit-frame-pointer -g1 -O1)
  if(KINRAY_FUZZ)
    if(NOT CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
      message(FATAL_ERROR "KINRAY_FUZZ needs clang (libFuzzer): -DCMAKE_CXX_COMPILER=clang++-14")
    endif()
    list(APPEND KINRAY_SANITIZER_FLAGS -fsanitize=fuzzer-no-link)
  endif()
  add_compile_options(${KINRAY_SANITIZER_FLAGS})
  add_link_options(-fsanitize=address,undefined)
endif()
