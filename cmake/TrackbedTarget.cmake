# Per-target settings for trackbed's own code: language level and warnings.
# Used instead of global CMAKE_CXX_FLAGS edits: one target per folder, each with its
# own settings (docs/architecture.md).
function(trackbed_settings target)
  get_target_property(_type ${target} TYPE)
  if(_type STREQUAL "INTERFACE_LIBRARY")
    target_compile_features(${target} INTERFACE cxx_std_17)
    return()
  endif()
  target_compile_features(${target} PUBLIC cxx_std_17)
  # The libraries are linked into the Python module (a shared object) as well as into
  # the programs: position-independent, without semantic interposition (nothing
  # replaces their functions at load time), so that the compiler still inlines them.
  if(_type STREQUAL "STATIC_LIBRARY")
    set_target_properties(${target} PROPERTIES POSITION_INDEPENDENT_CODE ON)
    target_compile_options(${target} PRIVATE -fno-semantic-interposition)
  endif()
  set_target_properties(${target} PROPERTIES CXX_EXTENSIONS OFF)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow
                         -Wnon-virtual-dtor -Wold-style-cast)
  if(TRACKBED_WERROR)
    target_compile_options(${target} PRIVATE -Werror)
  endif()
  # A sanitizer build folder (scripts/sanitize.sh): trackbed's own code instrumented,
  # every report fatal so that the test reporting it fails; the libraries pass the
  # link option on to the programs that link them.
  if(TRACKBED_SANITIZE)
    target_compile_options(${target} PRIVATE -fsanitize=${TRACKBED_SANITIZE}
                           -fno-sanitize-recover=all -fno-omit-frame-pointer)
    target_link_options(${target} PUBLIC -fsanitize=${TRACKBED_SANITIZE})
  endif()
  # A unity build includes sources into one another, which gcc takes for headers that
  # give a type internal linkage.
  if(CMAKE_UNITY_BUILD)
    target_compile_options(${target} PRIVATE -Wno-subobject-linkage)
  endif()
endfunction()
