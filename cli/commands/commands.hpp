// The commands of the raykernel CLI, as main dispatches them: `raykernel COMMAND ARGS...` runs
// run_COMMAND(ARGS) (argv without the program and command names). Each reads ARGS with its option table
// (common/options.hpp), writes through std::cout and returns its exit status: exit_usage (2) after
// "raykernel: I/O error writing standard output: REASON" when its output could not be written
// (common/io.hpp). The stream code of each command (the part tests and fuzzers drive) is declared in the
// command's own header.
#pragma once

#include "common/options.hpp"

#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace raykernel::cli {

struct Command {
  std::string_view name;
  int (*run)(const std::vector<std::string>& args);
  // The table `run` reads ARGS with, over destinations of its own (for the tests that go through every option).
  OwnedCommandLine (*command_line)();
};

// Every command, in the order `raykernel --help` lists them.
[[nodiscard]] std::span<const Command> commands();

// The whole tool on its arguments (the command and its options, without the program name): the standard streams
// switched to raykernel's checked ones, the command run, its exit status returned (cli/run_main.cpp).
int run_main(const std::vector<std::string>& arguments);

int run_classify(const std::vector<std::string>& args);  // plane_classify.cpp
OwnedCommandLine classify_command_line();
int run_nearest(const std::vector<std::string>& args);  // plane_nearest.cpp (--mesh: mesh_nearest.cpp)
OwnedCommandLine nearest_command_line();
int run_inside(const std::vector<std::string>& args);  // mesh_inside.cpp
OwnedCommandLine inside_command_line();
int run_closest(const std::vector<std::string>& args);  // mesh_closest.cpp
OwnedCommandLine closest_command_line();
int run_occluded(const std::vector<std::string>& args);  // mesh_occluded.cpp
OwnedCommandLine occluded_command_line();
int run_hits(const std::vector<std::string>& args);  // mesh_hits.cpp
OwnedCommandLine hits_command_line();
int run_watertight(const std::vector<std::string>& args);  // watertight.cpp
OwnedCommandLine watertight_command_line();
int run_triangle(const std::vector<std::string>& args);  // triangle.cpp
OwnedCommandLine triangle_command_line();
int run_sphere(const std::vector<std::string>& args);  // sphere.cpp
OwnedCommandLine sphere_command_line();
int run_spawn(const std::vector<std::string>& args);  // spawn.cpp
OwnedCommandLine spawn_command_line();
int run_spawn_audit(const std::vector<std::string>& args);  // spawn_audit.cpp
OwnedCommandLine spawn_audit_command_line();
int run_render(const std::vector<std::string>& args);  // render.cpp
OwnedCommandLine render_command_line();
int run_demo(const std::vector<std::string>& args);  // demo.cpp
OwnedCommandLine demo_command_line();

}  // namespace raykernel::cli
