// The commands of the raykernel CLI, as main dispatches them: `raykernel COMMAND ARGS...` runs
// run_COMMAND(ARGS) (argv without the program and command names; "--" ends the options). Each writes through
// std::cout and returns its exit status: exit_usage (2) after "raykernel: I/O error writing standard output:
// REASON" when its output could not be written (common/io.hpp). The stream code of each command (the part
// tests and fuzzers drive) is declared in the command's own header.
#pragma once

#include <string>
#include <vector>

namespace raykernel::cli {

int run_classify(const std::vector<std::string>& args);    // plane_classify.cpp
int run_nearest(const std::vector<std::string>& args);     // plane_nearest.cpp (--mesh: mesh_nearest.cpp)
int run_triangle(const std::vector<std::string>& args);    // triangle.cpp
int run_inside(const std::vector<std::string>& args);      // mesh_inside.cpp
int run_watertight(const std::vector<std::string>& args);  // watertight.cpp
int run_render(const std::vector<std::string>& args);      // render.cpp
int run_demo(const std::vector<std::string>& args);        // demo.cpp

}  // namespace raykernel::cli
