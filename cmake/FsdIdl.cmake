# Types from the IDL files of daemon/dds/idl (ROS 2 messages as the middleware sees them), generated at build time.
#   fsd_idl_library(NAME fastddsgen|idlc IDL_DIR FILES pkg/msg/T.idl ...)
# fastddsgen (Fast DDS, the daemon's bridge) writes T.h/.cxx and TPubSubTypes.h/.cxx; idlc (Cyclone DDS, the
# tests' independent reader) writes T.h/.c. Either goes to <build>/<pkg>/msg/, the layout the generated code's own
# #include "pkg/msg/T.h" expects. Each run may also write the files it included; only the named file's are built.
function(fsd_idl_library name generator idl_dir)
  set(out_root ${CMAKE_CURRENT_BINARY_DIR}/${name}_gen)
  file(GLOB_RECURSE all_idl CONFIGURE_DEPENDS ${idl_dir}/*.idl)
  set(srcs)
  foreach(rel ${ARGN})
    get_filename_component(sub ${rel} DIRECTORY)
    get_filename_component(base ${rel} NAME_WE)
    set(out ${out_root}/${sub})
    if(generator STREQUAL "fastddsgen")
      set(outputs ${out}/${base}.h ${out}/${base}.cxx ${out}/${base}PubSubTypes.h ${out}/${base}PubSubTypes.cxx)
      set(cmd ${FASTDDSGEN} -replace -I ${idl_dir} -d ${out} ${idl_dir}/${rel})
      list(APPEND srcs ${out}/${base}.cxx ${out}/${base}PubSubTypes.cxx)
    else()
      set(outputs ${out}/${base}.h ${out}/${base}.c)
      set(cmd ${IDLC} -I ${idl_dir} ${idl_dir}/${rel})
      list(APPEND srcs ${out}/${base}.c)
    endif()
    add_custom_command(OUTPUT ${outputs} COMMAND ${CMAKE_COMMAND} -E make_directory ${out}
                       COMMAND ${cmd} > ${out}/${base}.${generator}.log 2>&1 WORKING_DIRECTORY ${out}
                       DEPENDS ${all_idl} COMMENT "${generator} ${rel}" VERBATIM)
  endforeach()
  set(${name}_SOURCES ${srcs} CACHE INTERNAL "the generated sources of ${name}")
  set(${name}_INCLUDE_DIR ${out_root} CACHE INTERNAL "where ${name}'s generated headers are")
  add_library(${name} STATIC ${srcs})
  set_target_properties(${name} PROPERTIES POSITION_INDEPENDENT_CODE ON)
  target_include_directories(${name} SYSTEM PUBLIC ${out_root})
endfunction()
