#include "commands/commands.hpp"

namespace raykernel::cli {

std::span<const Command> commands() {
  static constexpr Command all[] = {
      {"classify", run_classify, classify_command_line},
      {"nearest", run_nearest, nearest_command_line},
      {"inside", run_inside, inside_command_line},
      {"closest", run_closest, closest_command_line},
      {"occluded", run_occluded, occluded_command_line},
      {"hits", run_hits, hits_command_line},
      {"watertight", run_watertight, watertight_command_line},
      {"triangle", run_triangle, triangle_command_line},
      {"sphere", run_sphere, sphere_command_line},
      {"spawn", run_spawn, spawn_command_line},
      {"spawn-audit", run_spawn_audit, spawn_audit_command_line},
      {"render", run_render, render_command_line},
      {"demo", run_demo, demo_command_line},
  };
  return all;
}

}  // namespace raykernel::cli
