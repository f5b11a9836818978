# Installs the package from BUILD_DIR into WORK_DIR/prefix, then configures, builds and
# runs the consumer project against it. Any failing step fails the test.
file(REMOVE_RECURSE ${WORK_DIR})
execute_process(COMMAND ${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${WORK_DIR}/prefix
                RESULT_VARIABLE rc OUTPUT_QUIET)
if(rc) message(FATAL_ERROR "cmake --install failed: ${rc}") endif()
execute_process(COMMAND ${CMAKE_COMMAND} -S ${SOURCE_DIR}/test/Polycube_IGA/consumer
                -B ${WORK_DIR}/build -DCMAKE_BUILD_TYPE=Release
                -DCMAKE_PREFIX_PATH=${WORK_DIR}/prefix
                RESULT_VARIABLE rc)
if(rc) message(FATAL_ERROR "configuring the consumer failed: ${rc}") endif()
execute_process(COMMAND ${CMAKE_COMMAND} --build ${WORK_DIR}/build RESULT_VARIABLE rc)
if(rc) message(FATAL_ERROR "building the consumer failed: ${rc}") endif()
execute_process(COMMAND ${WORK_DIR}/build/consumer RESULT_VARIABLE rc)
if(rc) message(FATAL_ERROR "the consumer program failed: ${rc}") endif()
