# Registers the packaging tests: the consumer project in this directory is built against an
# installed cellforge (find_package) and against the source tree (add_subdirectory).
# Included from tests/CMakeLists.txt. The consumer gets no sanitizer or developer flags.
get_property(_cellforge_multi_config GLOBAL PROPERTY GENERATOR_IS_MULTI_CONFIG)
if(_cellforge_multi_config)
  set(_cellforge_consumer_config "$<CONFIG>")
elseif(CMAKE_BUILD_TYPE)
  set(_cellforge_consumer_config "${CMAKE_BUILD_TYPE}")
else()
  set(_cellforge_consumer_config Release)
endif()
set(_cellforge_consumer_modes subdirectory)
if(CELLFORGE_INSTALL)
  list(PREPEND _cellforge_consumer_modes package)
endif()
foreach(mode IN LISTS _cellforge_consumer_modes)
  add_test(NAME consumer_${mode}
           COMMAND "${CMAKE_COMMAND}"
                   "-DMODE=${mode}"
                   "-DCELLFORGE_SOURCE_DIR=${PROJECT_SOURCE_DIR}"
                   "-DCELLFORGE_BINARY_DIR=${PROJECT_BINARY_DIR}"
                   "-DWORK_DIR=${CMAKE_BINARY_DIR}/consumer-${mode}"
                   "-DPREFIX=${CMAKE_BINARY_DIR}/consumer-prefix"
                   "-DGENERATOR=${CMAKE_GENERATOR}"
                   "-DMAKE_PROGRAM=${CMAKE_MAKE_PROGRAM}"
                   "-DCXX_COMPILER=${CMAKE_CXX_COMPILER}"
                   "-DCONFIG=${_cellforge_consumer_config}"
                   -P "${CMAKE_CURRENT_LIST_DIR}/run-consumer.cmake")
  set_tests_properties(consumer_${mode} PROPERTIES LABELS "packaging" TIMEOUT 600)
endforeach()
unset(_cellforge_consumer_config)
unset(_cellforge_consumer_modes)
unset(_cellforge_multi_config)
