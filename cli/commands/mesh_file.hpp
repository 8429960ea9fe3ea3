// The mesh file of the mesh commands (nearest --mesh, hits, occluded, inside, watertight, spawn-audit): read, then prepared for queries.
#pragma once

#include <raykernel/mesh_queries.hpp>

#include <iosfwd>
#include <optional>
#include <string>
#include <string_view>

namespace raykernel::cli {

// The mesh in a file, or nothing after printing on `err` "raykernel COMMAND: cannot open mesh file 'FILE':
// REASON" (the system's reason, as for every input of every command), or "raykernel: FILE:LINE: REASON" (or
// "FILE: byte N: REASON", "FILE: REASON") for what is wrong in it (docs/contract.md §7: an unreadable mesh is
// exit status 2, nothing on stdout).
[[nodiscard]] std::optional<Mesh> read_mesh_file(std::string_view command, const std::string& path, std::ostream& err);

// The mesh prepared for queries (its BVH built), with "not enough memory" naming it (common/failure.hpp).
[[nodiscard]] PreparedMesh prepare_mesh(Mesh&& mesh, const std::string& path);

// read_mesh_file, then prepare_mesh: the prepared mesh, or nothing after printing why.
[[nodiscard]] std::optional<PreparedMesh> load_prepared_mesh(std::string_view command, const std::string& path,
                                                             std::ostream& err);

// The same for the commands whose mesh is the option `--mesh FILE`: nothing after printing "raykernel COMMAND:
// --mesh FILE is required (see raykernel COMMAND --help)" when it is absent.
[[nodiscard]] std::optional<PreparedMesh> load_mesh_option(std::string_view command,
                                                           const std::optional<std::string>& path, std::ostream& err);

}  // namespace raykernel::cli
