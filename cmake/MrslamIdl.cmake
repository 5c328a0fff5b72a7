# mrslam_generate_idl(OUT_SOURCES OUT_DIR idl_file...): runs fastddsgen on each IDL file at build
# time and returns the generated sources. Generated code lives in the build tree only.
find_program(FASTDDSGEN_EXECUTABLE fastddsgen REQUIRED)

function(mrslam_generate_idl out_sources out_dir)
  set(generated)
  foreach(idl_file ${ARGN})
    get_filename_component(idl_abs ${idl_file} ABSOLUTE)
    get_filename_component(idl_name ${idl_file} NAME_WE)
    set(outputs
        ${out_dir}/${idl_name}.h ${out_dir}/${idl_name}.cxx
        ${out_dir}/${idl_name}PubSubTypes.h ${out_dir}/${idl_name}PubSubTypes.cxx)
    add_custom_command(
      OUTPUT ${outputs}
      COMMAND ${CMAKE_COMMAND} -E make_directory ${out_dir}
      COMMAND ${FASTDDSGEN_EXECUTABLE} -replace -cs -d ${out_dir} ${idl_abs}
      DEPENDS ${idl_abs}
      COMMENT "fastddsgen ${idl_name}.idl"
      VERBATIM)
    list(APPEND generated ${outputs})
  endforeach()
  set(${out_sources} ${generated} PARENT_SCOPE)
endfunction()
