# Every dependency comes from a Debian 12 package (scripts/setup.sh installs them); nothing is
# downloaded at build time.
find_package(Eigen3 3.4 REQUIRED NO_MODULE)
find_package(OpenCV 4 REQUIRED COMPONENTS core imgproc calib3d imgcodecs)
find_package(yaml-cpp REQUIRED)
find_package(CLI11 REQUIRED)
find_package(nlohmann_json 3 REQUIRED)
find_package(Threads REQUIRED)
if(AAVIO_BUILD_TESTS)
  find_package(GTest REQUIRED)
endif()
if(AAVIO_BUILD_BENCHMARKS)
  find_package(benchmark REQUIRED)
endif()
