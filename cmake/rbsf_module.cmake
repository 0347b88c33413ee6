# rbsf_add_module(NAME SOURCE...): the library rbsf_<NAME> of one module, exported as
# rbsf::<NAME> (alias and installed name), its public headers in the calling folder's
# include/, position-independent, C++20. Each module then adds what it links.
function(rbsf_add_module name)
  add_library(rbsf_${name} ${ARGN})
  add_library(rbsf::${name} ALIAS rbsf_${name})
  set_target_properties(rbsf_${name} PROPERTIES EXPORT_NAME ${name} OUTPUT_NAME rbsf_${name}
                                                POSITION_INDEPENDENT_CODE ON)
  target_include_directories(rbsf_${name} PUBLIC
    $<BUILD_INTERFACE:${CMAKE_CURRENT_SOURCE_DIR}/include>
    $<INSTALL_INTERFACE:include>)
  target_compile_features(rbsf_${name} PUBLIC cxx_std_20)
endfunction()
