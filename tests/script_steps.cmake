# Shared by the CTest scripts run with `cmake -P`: argument checks and fail-fast command steps.

# require_script_arguments(NAME...): stops unless each -DNAME=... was given.
function(require_script_arguments)
  foreach(var IN LISTS ARGN)
    if(NOT DEFINED ${var})
      message(FATAL_ERROR "${CMAKE_SCRIPT_MODE_FILE} needs -D${var}=...")
    endif()
  endforeach()
endfunction()

# step(COMMAND...): runs it; stops the script with the command line when it fails.
function(step)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE result)
  if(NOT result EQUAL 0)
    string(REPLACE ";" " " shown "${ARGN}")
    message(FATAL_ERROR "failed (${result}): ${shown}")
  endif()
endfunction()
