// The raykernel command-line tool: raykernel::cli::run_main (run_main.cpp) on the arguments.
#include "commands/commands.hpp"

#include <iostream>
#include <string>
#include <vector>

int main(int argc, char** argv) {
  std::ios::sync_with_stdio(false);
  return raykernel::cli::run_main(std::vector<std::string>(argv + 1, argv + argc));
}
