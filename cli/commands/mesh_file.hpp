// The mesh file of the mesh commands (nearest --mesh, inside, watertight): read, then prepared for queries.
#pragma once

#include <raykernel/mesh_queries.hpp>

#include <iosfwd>
#include <optional>
#include <string>

namespace raykernel::cli {

// The mesh in a file, or nothing after printing "raykernel: FILE:LINE: REASON" (or "FILE: byte N: REASON",
// "FILE: REASON") on `err` (docs/contract.md §7: an unreadable mesh is exit status 2, nothing on stdout).
[[nodiscard]] std::optional<Mesh> read_mesh_file(const std::string& path, std::ostream& err);

// The mesh prepared for queries (its BVH built), with "not enough memory" naming it (common/failure.hpp).
[[nodiscard]] PreparedMesh prepare_mesh(Mesh&& mesh, const std::string& path);

}  // namespace raykernel::cli
