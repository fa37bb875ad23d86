# forensim_add_module(<name> DEPS <targets...> [PRIVATE_DEPS <targets...>])
# Builds src/<name>/*.cpp into the static library forensim_<name> (alias forensim::<name>).
# Public headers are included as "<name>/<file>.hpp" (src/ is on the include path).
function(forensim_add_module name)
  cmake_parse_arguments(ARG "" "" "DEPS;PRIVATE_DEPS" ${ARGN})
  file(GLOB sources CONFIGURE_DEPENDS "${CMAKE_CURRENT_SOURCE_DIR}/${name}/*.cpp")
  if(NOT sources)
    return()  # module not written yet
  endif()
  add_library(forensim_${name} STATIC ${sources})
  add_library(forensim::${name} ALIAS forensim_${name})
  target_include_directories(forensim_${name} PUBLIC
    "$<BUILD_INTERFACE:${PROJECT_SOURCE_DIR}/src>"
    "$<BUILD_INTERFACE:${PROJECT_BINARY_DIR}/generated>")
  target_link_libraries(forensim_${name} PUBLIC ${ARG_DEPS} PRIVATE ${ARG_PRIVATE_DEPS} forensim_warnings
                        forensim_sanitizers)
  target_link_libraries(forensim_${name} INTERFACE forensim_sanitizers)
  target_link_libraries(forensim INTERFACE forensim_${name})
endfunction()
