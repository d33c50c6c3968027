# Unity ("jumbo") builds: CI's strict and sanitizer builds compile each target's sources in
# batches of 8 per translation unit (-DCMAKE_UNITY_BUILD=ON, docs/ci.md), which halves the
# compile time; -DGS_UNITY_TESTS=ON batches only the test suites. A plain configure (the
# README's first command, .ci/demo) compiles every file alone, where a missing #include
# shows. Files whose file-local names (anonymous namespaces) collide with a neighbour's
# in one batch are compiled alone: list them here, relative to the project root, when a
# unity build reports "redefinition of" or "ambiguous" for a name in an anonymous namespace.
set(GS_UNITY_ALONE
  formats/src/ply_reader.cpp
  formats/src/vdb_child.cpp
  qnv/src/position_model.cpp
  qnv/src/tileset_index.cpp
  qnv/src/volume_slabs.cpp
  render/src/surface_programs.cpp
  session/src/volume_input.cpp
  geometry/src/geometry_indexed.cpp
  geometry/src/geometry_primitives.cpp
  vrml/src/node_model_data_0.cpp
  vrml/src/node_model_data_1.cpp
  vrml/src/node_model_data_2.cpp
  vrml/src/node_model_data_3.cpp
  vrml/src/node_model_data_4.cpp
  vrml/src/node_model_data_5.cpp
  tests/encodings/test_x3d_json.cpp
  tests/encodings/test_x3d_xml.cpp
  tests/geometry/test_texcoord_3d.cpp
  tests/formats/test_mesh_readers.cpp
  tests/formats/test_ply_stream.cpp
  tests/formats/test_volume_readers.cpp
  tests/net/test_http_faults.cpp
  tests/net/test_http_nginx.cpp
  tests/net/test_transfer.cpp
  tests/qnv/test_entropy_fast.cpp
  tests/qnv/test_golden.cpp
  tests/qnv/test_stream_model.cpp
  tests/qnv/test_tileset_index.cpp
  tests/app/test_window_keys.cpp
  tests/render/test_multi_texture.cpp
  tests/render/test_line_fill_properties.cpp
  tests/render/test_environmental_effects.cpp
  tests/render/test_composed_shaders.cpp
  tests/render/test_texture_3d.cpp
  tests/render/test_texture_generation.cpp
  tests/render/test_image_cube_map.cpp
  tests/render/test_generated_cube_map.cpp
  tests/render/test_volume_data.cpp
  tests/render/test_layering.cpp
  tests/render/test_worlds.cpp
  tests/runtime/test_key_sensors.cpp
  tests/render/test_movie_share.cpp
  tests/render/test_offscreen.cpp
  tests/render/test_splat_cpu.cpp
  tests/render/test_splat_gpu.cpp
  tests/scene/test_picking.cpp
  tests/scene/test_text_mesh.cpp
  tests/session/test_volume_input.cpp
  tests/geometry/test_geometry_x3d.cpp
  tests/encodings/test_x3d_json.cpp
  tests/encodings/test_x3d_xml.cpp
  tests/render/test_worlds.cpp
  tests/gltf/test_gltf_scene.cpp
  tests/app/test_ooc_tileset_cli.cpp
  tests/app/test_progressive.cpp)

# Marks the listed files under `subdir` (a prefix of their paths) as compiled alone, in the
# current directory's scope (source file properties are per directory).
function(gs_unity_alone subdir)
  if(NOT CMAKE_UNITY_BUILD AND NOT (GS_UNITY_TESTS AND subdir MATCHES "^tests/"))
    return()
  endif()
  foreach(f IN LISTS GS_UNITY_ALONE)
    if(f MATCHES "^${subdir}")
      set_source_files_properties(${PROJECT_SOURCE_DIR}/${f} PROPERTIES SKIP_UNITY_BUILD_INCLUSION ON)
    endif()
  endforeach()
endfunction()
