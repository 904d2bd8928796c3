# Warnings for the project's own targets (never for third-party headers, which are included as SYSTEM).
function(preskin_warnings target)
  target_compile_options(${target} PRIVATE
    $<$<COMPILE_LANG_AND_ID:CXX,GNU,Clang>:-Wall -Wextra -Wpedantic -Wshadow -Wconversion -Wno-sign-conversion
      -Wnon-virtual-dtor -Wold-style-cast -Woverloaded-virtual -Wnull-dereference -Wdouble-promotion
      # Vulkan structs are zero-filled by naming only sType: {VK_STRUCTURE_TYPE_...}.
      -Wno-missing-field-initializers>)
  if(PRESKIN_WARNINGS_AS_ERRORS)
    target_compile_options(${target} PRIVATE $<$<COMPILE_LANG_AND_ID:CXX,GNU,Clang>:-Werror>)
  endif()
endfunction()
