# mrslam_set_warnings(target): the project's warning flags on one target.
function(mrslam_set_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow -Wnon-virtual-dtor)
  if(MRSLAM_WERROR)
    target_compile_options(${target} PRIVATE -Werror)
  endif()
endfunction()
