# Runs `clpt render SCENE -o WORK/out.exr` on a broken scene and checks that it
#  - exits with code 3 (bad scene),
#  - prints exactly the message on the scene's first line ("# expect: MESSAGE", @FILE@ = path),
#  - leaves no output file (neither out.exr nor out.png) behind.
#   cmake -DCLPT=clpt -DSCENE=bad.toml -DWORK=dir -P run_bad_scene.cmake
file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK})
# file(READ) rather than file(STRINGS): messages may hold ';', which a CMake list would split.
file(READ "${SCENE}" content)
string(FIND "${content}" "\n" eol)
string(SUBSTRING "${content}" 0 ${eol} first_line)
string(REGEX REPLACE "^# expect: " "" expected "${first_line}")
if(expected STREQUAL first_line)
  message(FATAL_ERROR "${SCENE}: first line must be '# expect: MESSAGE'")
endif()
string(REPLACE "@FILE@" "${SCENE}" expected "${expected}")
execute_process(COMMAND ${CLPT} render ${SCENE} -o ${WORK}/out.exr
                RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT code EQUAL 3)
  message(FATAL_ERROR "exit code ${code}, expected 3\nstdout: ${out}\nstderr: ${err}")
endif()
string(STRIP "${err}" err)
if(NOT err STREQUAL "clpt: error: ${expected}")
  message(FATAL_ERROR "message mismatch\nexpected: clpt: error: ${expected}\nactual:   ${err}")
endif()
file(GLOB leftovers ${WORK}/*)
if(leftovers)
  message(FATAL_ERROR "files left behind: ${leftovers}")
endif()
