# Every third-party package Caligo links, found once. See ../shared/DEPENDENCIES.md for the pitfalls.
find_package(TBB CONFIG REQUIRED)
find_package(embree 3 CONFIG REQUIRED)
find_package(OpenEXR CONFIG REQUIRED)
find_package(Imath CONFIG REQUIRED)
find_package(OpenImageIO 2.4 CONFIG REQUIRED)
# PNG previews through libpng directly (CMake's FindPNG; OpenImageIO only in its plugin).
find_package(ZLIB REQUIRED)
find_package(PNG REQUIRED)
find_package(nlohmann_json CONFIG REQUIRED)
find_package(CLI11 CONFIG REQUIRED)
find_package(fmt CONFIG REQUIRED)
find_package(tinyobjloader CONFIG REQUIRED)
find_package(TinyGLTF CONFIG REQUIRED)
find_package(Threads REQUIRED)
# OpenVDB ships only a Find module, beside old FindTBB/FindOpenEXR modules that would shadow
# the packages' own configs: TBB, OpenEXR and Imath are found above with CONFIG first.
# NanoVDB (header-only) comes with it as a component.
list(APPEND CMAKE_MODULE_PATH "/usr/lib/${CMAKE_LIBRARY_ARCHITECTURE}/cmake/OpenVDB")
find_package(OpenVDB REQUIRED COMPONENTS openvdb nanovdb)
# NanoVDB is header-only, but its imported target links libopenvdb (~30 ms and ~28 MB of
# start-up in every process): drop the link. Only the caligo_vdb.so plugin links OpenVDB.
set_target_properties(OpenVDB::nanovdb PROPERTIES INTERFACE_LINK_LIBRARIES "")
# Mesh volumes read PLY through assimp (tinyobjloader and tinygltf cover OBJ and glTF).
find_package(assimp CONFIG REQUIRED)
# xsimd 8.1 (header-only) vectorises the real-time passes. Its exported target links an
# `xtl` library that Debian's package does not need or ship: drop the link.
find_package(xsimd CONFIG REQUIRED)
set_target_properties(xsimd PROPERTIES INTERFACE_LINK_LIBRARIES "")
# cpp-httplib 0.11 (Debian's libcpp-httplib-dev builds it as a shared library, without a CMake
# package): the preview server of `caligo render --preview` (apps/caligo/preview_server.cpp).
find_library(CPP_HTTPLIB_LIBRARY NAMES cpp-httplib REQUIRED)
find_path(CPP_HTTPLIB_INCLUDE_DIR httplib.h REQUIRED)
add_library(cpp_httplib INTERFACE IMPORTED)
set_target_properties(cpp_httplib PROPERTIES INTERFACE_LINK_LIBRARIES "${CPP_HTTPLIB_LIBRARY}"
                                             INTERFACE_INCLUDE_DIRECTORIES "${CPP_HTTPLIB_INCLUDE_DIR}")
# Open MPI (optional): `mpirun caligo render` splits a frame over processes (src/distributed/).
# The C API only (no deprecated C++ bindings). Without it the project builds single-process.
set(MPI_CXX_SKIP_MPICXX ON)
find_package(MPI COMPONENTS CXX)
if(CALIGO_BUILD_TESTS)
  find_package(GTest CONFIG REQUIRED)
endif()
if(CALIGO_BUILD_BENCH)
  find_package(benchmark CONFIG REQUIRED)
endif()

# OpenImageIO's imported target names /usr/include/opencv4, which only exists with
# libopencv-core-dev installed; CMake refuses to generate with a missing include path.
get_target_property(_oiio_includes OpenImageIO::OpenImageIO INTERFACE_INCLUDE_DIRECTORIES)
if(_oiio_includes)
  list(FILTER _oiio_includes EXCLUDE REGEX "opencv4")
  set_target_properties(OpenImageIO::OpenImageIO PROPERTIES INTERFACE_INCLUDE_DIRECTORIES "${_oiio_includes}")
endif()
