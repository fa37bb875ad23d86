# Every third-party dependency of forensim is found here, from the system (Debian packages installed by
# scripts/install-deps). Each ends up as an imported target; modules link only what they use.

find_package(Threads REQUIRED)
find_package(Eigen3 3.4 REQUIRED NO_MODULE)                 # Eigen3::Eigen
find_package(TBB REQUIRED CONFIG)                           # TBB::tbb
find_package(embree 3 REQUIRED)                             # embree
find_package(CGAL REQUIRED)                                 # CGAL::CGAL
find_package(assimp REQUIRED)                               # assimp::assimp
find_package(TinyGLTF REQUIRED)                             # TinyGLTF::TinyGLTF (shared library; see src/mesh_io/tinygltf_implementation.cpp)
find_package(PNG REQUIRED)                                  # PNG::PNG
find_package(ZLIB REQUIRED)                                 # ZLIB::ZLIB
find_package(TIFF REQUIRED)                                 # TIFF::TIFF
find_package(OpenEXR REQUIRED CONFIG)                       # OpenEXR::OpenEXR
find_package(GDCM REQUIRED CONFIG HINTS /usr/lib/${CMAKE_LIBRARY_ARCHITECTURE}/gdcm-3.0)  # gdcmMSFF
find_package(nlohmann_json 3.10 REQUIRED)                   # nlohmann_json::nlohmann_json
find_package(CLI11 REQUIRED)                                # CLI11::CLI11
find_package(fmt REQUIRED)                                  # fmt::fmt
find_package(spdlog REQUIRED)                               # spdlog::spdlog
find_package(PkgConfig REQUIRED)

# OpenVDB ships a Find module (not a config) in its own cmake folder.
list(APPEND CMAKE_MODULE_PATH "/usr/lib/${CMAKE_LIBRARY_ARCHITECTURE}/cmake/OpenVDB")
find_package(OpenVDB REQUIRED)                              # OpenVDB::openvdb

# stb: Debian builds the implementations into libstb; headers live in /usr/include/stb.
pkg_check_modules(STB REQUIRED IMPORTED_TARGET stb)         # PkgConfig::STB

# cpp-httplib (forensim serve): Debian builds it as a library; its pkg-config flags select the features it
# was built with (they change the classes' layout, so they must match).
pkg_check_modules(HTTPLIB REQUIRED IMPORTED_TARGET cpp-httplib)  # PkgConfig::HTTPLIB

# SuiteSparse 5 (CHOLMOD) has no CMake config; find the libraries directly. OpenBLAS provides BLAS/LAPACK.
find_path(CHOLMOD_INCLUDE_DIR cholmod.h PATH_SUFFIXES suitesparse REQUIRED)
find_library(CHOLMOD_LIBRARY cholmod REQUIRED)
find_library(SUITESPARSECONFIG_LIBRARY suitesparseconfig REQUIRED)
find_library(AMD_LIBRARY amd REQUIRED)
find_library(COLAMD_LIBRARY colamd REQUIRED)
find_library(OPENBLAS_LIBRARY openblas REQUIRED)
add_library(forensim_cholmod INTERFACE)
target_include_directories(forensim_cholmod SYSTEM INTERFACE "${CHOLMOD_INCLUDE_DIR}")
target_link_libraries(forensim_cholmod INTERFACE "${CHOLMOD_LIBRARY}" "${AMD_LIBRARY}" "${COLAMD_LIBRARY}"
                      "${SUITESPARSECONFIG_LIBRARY}" "${OPENBLAS_LIBRARY}")
add_library(forensim::cholmod ALIAS forensim_cholmod)

# Fonts for captions in rendered pictures (fonts-dejavu-core).
find_file(FORENSIM_FONT_FILE DejaVuSans.ttf PATHS /usr/share/fonts/truetype/dejavu REQUIRED)

if(FORENSIM_WITH_TESTS)
  find_package(GTest REQUIRED)                              # GTest::gtest, GTest::gtest_main
  include(GoogleTest)
endif()
if(FORENSIM_WITH_BENCHMARKS)
  find_package(benchmark REQUIRED)                          # benchmark::benchmark
endif()
