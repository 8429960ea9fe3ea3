// Reading and preparing the mesh file of the mesh commands.
#include "commands/mesh_file.hpp"

#include "common/failure.hpp"
#include "common/limits.hpp"
#include "common/text_format.hpp"

#include <raykernel/io/mesh_file.hpp>

#include <new>
#include <ostream>
#include <string_view>

namespace raykernel::cli {

std::optional<Mesh> read_mesh_file(std::string_view command, const std::string& path, std::ostream& err) {
  const Doing doing("reading the mesh file " + quote(path, limits::quoted_token_bytes));
  try {
    return io::read_mesh(path);
  } catch (const io::mesh_file_error& e) {
    // A file that cannot be opened is reported as every command reports its inputs (common/stream_command);
    // what is wrong inside a file, with its line or byte offset (docs/contract.md §7).
    const std::string& reason = e.reason();
    if (e.position().kind == io::FilePosition::Kind::none && reason.starts_with("cannot open: "))
      err << "raykernel " << command << ": cannot open mesh file " << quote(path, path.size()) << ": "
          << printable(reason.substr(13)) << '\n';
    else if (e.position().kind == io::FilePosition::Kind::none && reason == "is a directory")
      err << "raykernel " << command << ": cannot open mesh file " << quote(path, path.size()) << ": Is a directory\n";
    else
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

std::optional<PreparedMesh> load_prepared_mesh(std::string_view command, const std::string& path, std::ostream& err) {
  std::optional<Mesh> mesh = read_mesh_file(command, path, err);
  if (!mesh) return std::nullopt;
  return prepare_mesh(std::move(*mesh), path);
}

std::optional<PreparedMesh> load_mesh_option(std::string_view command, const std::optional<std::string>& path,
                                             std::ostream& err) {
  if (!path) {
    err << "raykernel " << command << ": --mesh FILE is required (see raykernel " << command << " --help)\n";
    return std::nullopt;
  }
  return load_prepared_mesh(command, *path, err);
}

}  // namespace raykernel::cli
