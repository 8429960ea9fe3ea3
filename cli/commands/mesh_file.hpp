// The mesh file of the mesh commands (nearest --mesh, inside, watertight): read, then prepared for queries.
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

}  // namespace raykernel::cli
