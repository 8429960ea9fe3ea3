// The command-line tool inside the module (raykernel::cli::run_main), for the package's `raykernel` console script
// and `python -m raykernel` (raykernel/__main__.py): the same program as build/bin/raykernel, so that the replay
// commands raykernel.testing prints run after `pip install`. Only when the CLI is built (RAYKERNEL_BUILD_CLI).
#include "bindings.hpp"

#include <pybind11/stl.h>

#ifdef RAYKERNEL_PYTHON_WITH_CLI
#include "commands/commands.hpp"
#endif

#include <string>
#include <vector>

namespace raykernel::python {

void bind_cli(pybind11::module_& m) {
#ifdef RAYKERNEL_PYTHON_WITH_CLI
  m.def(
      "_cli_main",
      [](const std::vector<std::string>& arguments) {
        pybind11::gil_scoped_release release;  // a command may read standard input for as long as it is open
        return cli::run_main(arguments);
      },
      pybind11::arg("arguments"),
      "Runs the raykernel command-line tool on `arguments` (the command and its options) with the process's "
      "standard streams; returns its exit status. The console script `raykernel` and `python -m raykernel` call it.");
#else
  (void)m;
#endif
}

}  // namespace raykernel::python
