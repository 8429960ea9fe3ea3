// Reading and preparing the mesh file of the mesh commands.
#include "commands/mesh_file.hpp"

#include "common/failure.hpp"
#include "common/limits.hpp"
#include "common/text_format.hpp"

#include <raykernel/io/mesh_file.hpp>

#include <new>
#include <ostream>

namespace raykernel::cli {

std::optional<Mesh> read_mesh_file(const std::string& path, std::ostream& err) {
  const Doing doing("reading the mesh file " + quote(path, limits::quoted_token_bytes));
  try {
    return io::read_mesh(path);
  } catch (const io::mesh_file_error& e) {
    err << "raykernel: " << printable(e.what()) << '\n';
  } catch (const std::bad_alloc&) {
    err << "raykernel: " << printable(path) << ": not enough memory for the mesh\n";
  }
  return std::nullopt;
}

PreparedMesh prepare_mesh(Mesh&& mesh, const std::string& path) {
  const Doing doing("the mesh " + quote(path, limits::quoted_token_bytes) + " and its BVH");
  return PreparedMesh(std::move(mesh));  // valid: the readers return valid meshes
}

}  // namespace raykernel::cli
