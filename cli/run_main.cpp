// The raykernel command-line tool's dispatch to its subcommands (raykernel::cli::run_main, commands/commands.hpp):
// the program (main.cpp) and the Python package's `raykernel` console script and `python -m raykernel` run it.
#include "commands/commands.hpp"
#include "common/exit_status.hpp"
#include "common/failure.hpp"
#include "common/io.hpp"
#include "common/text_format.hpp"

#include <raykernel/raykernel.hpp>

#include <algorithm>
#include <iostream>
#include <span>
#include <string>
#include <vector>

namespace raykernel::cli {
namespace {

constexpr const char* overview = R"(raykernel: exact ray casting for binary64 inputs (planes, triangles, spheres, meshes), certified fast

usage: raykernel <command> [options]

commands:
  classify [FILE|-]   classify ray-plane queries, one per line (raykernel classify --help)
  nearest --planes FILE [RAYS|-]
                      the first plane each ray hits, decided exactly (raykernel nearest --help)
  nearest --mesh FILE [RAYS|-]
                      the first triangle of a mesh (OBJ, PLY, STL, OFF, glTF) each ray hits, exactly,
                      within the ray's interval when a line gives one
  inside --mesh FILE [POINTS|-]
                      whether each point is inside, outside or on a closed mesh, exactly
                      (raykernel inside --help)
  closest --mesh FILE [--signed] [POINTS|-]
                      the exact closest point of a mesh to each point: triangle, point, squared
                      distance (exact and rounded), distance correctly rounded (raykernel closest --help)
  occluded --mesh FILE [--segment] [RAYS|-]
                      whether anything blocks each ray within its interval, or each open
                      segment between two points, exactly (raykernel occluded --help)
  hits --mesh FILE [RAYS|-]
                      every triangle each ray hits within its interval, in exact order, and the
                      signed count of its owned crossings (raykernel hits --help)
  watertight FILE [--rays N] [--seed S] [--png OUT]
                      count leaks, double hits and missed vertices along random lines: owned
                      and closed rules, Moller-Trumbore, Embree (raykernel watertight --help)
  triangle [FILE|-]   intersect rays with triangles exactly, one query per line; owned or closed
                      rule (raykernel triangle --help)
  sphere [FILE|-]     intersect rays with spheres exactly, one query per line: where the origin
                      lies, miss/tangent/cross, correctly rounded roots (raykernel sphere --help)
  spawn [FILE|-]      the origin of a secondary ray that never re-hits the triangle it leaves,
                      in binary64 or binary32 (raykernel spawn --help)
  spawn-audit FILE [--hits N] [--seed S] [--scale-exponent E] [--png OUT]
                      check exactly how renderers' ray-offset methods (pbrt-v4, Ray Tracing
                      Gems/Cycles, Mitsuba 3, Embree, One Weekend) and spawn fare on a mesh:
                      self-hits, wrong side, first hits that differ (raykernel spawn-audit --help)
  render [SCENE.json] render a scene of planes, meshes and spheres to PNG, or the built-in demo scene;
                      can mark where the exact answer needed slower stages and where plain doubles
                      pick another surface (raykernel render --help)
  demo                run the built-in batch of hard queries and summarize it
  --version           print the version
  --help              this text
)";

}  // namespace

int run_main(const std::vector<std::string>& arguments) {
  use_checked_standard_streams();
  const std::vector<std::string> args(arguments.begin() + (arguments.empty() ? 0 : 1), arguments.end());
  const std::string command = arguments.empty() ? "" : arguments.front();
  if (command.empty() || command == "--help" || command == "-h" || command == "help") {
    std::cout << overview;
    return finish_standard_output(exit_ok);
  }
  if (command == "--version" || command == "version") {
    std::cout << "raykernel " << raykernel::version() << '\n';
    return finish_standard_output(exit_ok);
  }
  const std::span<const Command> all = commands();
  const auto found = std::find_if(all.begin(), all.end(), [&command](const Command& c) { return c.name == command; });
  if (found == all.end()) {
    std::cerr << "raykernel: unknown command " << quote(command) << "\n" << overview;
    return finish_standard_output(exit_usage);
  }
  int status = exit_usage;
  try {
    status = found->run(args);
  } catch (...) {
    // Nothing a command leaves uncaught ends in std::terminate: what was answered is kept, and exit 2.
    (void)flush_standard_output();
    return report_uncaught(command, std::current_exception());
  }
  // Every command ends its own output; this catches anything written after (the message is printed once),
  // and a failed write to standard error (requested statistics or a report lost) too.
  return finish_standard_output(status);
}

}  // namespace raykernel::cli
