// Every command's command line, read one way: a table of the options the command takes (name, value, help,
// where the value goes and what it may be), one parse loop for every command, and the options section of each
// command's --help generated from its table.
//
//   - An option that takes a value takes it as `--name VALUE` or `--name=VALUE`; one whose value may be left
//     out (`--show-stages[=FILE]`) takes it only after '=', so that the argument after it stays an operand.
//     A short alias (`-o`) takes its value as the next argument. The value is taken as it is, even when it
//     starts with '-' (`-o -`).
//   - `--` ends the options: every later argument is an operand, even one starting with '-'. `-` alone is an
//     operand (standard input). Every command answers `--help` and `-h`.
//   - Options are read in order, each value stored as it is read; the first mistake ends the command line
//     with one message, "raykernel COMMAND: ..." on stderr, and exit status 2:
//       unknown option '--x' (see raykernel COMMAND --help)
//       --x needs a value (WHAT IT TAKES)
//       bad value for --x: 'V' (WHAT IT TAKES)                    a value out of range too
//       --x given twice                                           an option that takes a value
//       --x takes no value ('--x=V')
//       more than one WHAT ('A', 'B')                             the one operand a command takes
//       unexpected argument 'A' (see raykernel COMMAND --help)    a command that takes no operand
//     (--x as it was spelled: "-o needs a value ...").
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace raykernel::cli {

// What an option does with its argument: whether it takes a value, where the value goes, what a valid value is.
// The functions below make them (flag, action, integer, one_of, file, optional_file).
struct Value {
  enum class Takes { nothing, value, optional_value };
  Takes takes = Takes::nothing;
  std::string metavar;  // how the help shows the value: FILE, N, owned|closed
  std::string accepts;  // what a valid value is, for the messages: "an integer from 1 to 256"
  std::string range;    // the range of an integer ("1 to 256"), which the help adds to the option's help
  // Stores the value ("" for a flag, and for an optional value left out); false when it is not valid.
  std::function<bool(const std::string& value)> store;
  // An action (--print-demo-scene): once it is read, the rest of the command line is not.
  bool ends_command_line = false;
};

// A row of a command's table: {"--hex", flag(options.hex), "print T as a hexadecimal float"}.
struct Option {
  Option(std::string name, Value value, std::string help)
      : name(std::move(name)), value(std::move(value)), help(std::move(help)) {}
  Option(std::string name, std::string alias, Value value, std::string help)
      : name(std::move(name)), alias(std::move(alias)), value(std::move(value)), help(std::move(help)) {}

  std::string name;   // the long name: --path
  std::string alias;  // a short name (-o), or none
  Value value;
  std::string help;  // one paragraph, wrapped by the help
};

// The one operand a command may take: a file, "-" for standard input.
struct Operand {
  std::string metavar;  // as the help names it: FILE, RAYS, SCENE.json
  std::string what;     // as messages name it: "input file"
  std::optional<std::string>* destination = nullptr;
};

struct CommandLine {
  std::string command;  // "classify"
  std::vector<Option> options;
  std::optional<Operand> operand;  // none: the command takes no operand
  std::string help_before;         // the help's usage and description, before "options:"
  std::string help_after;          // after the options (formats, exit status), or nothing
};

// A command line over destinations of its own, kept alive with it: what tests that go through every option of
// every command read into. owned_command_line(command_line) makes one from a command's table function.
struct OwnedCommandLine {
  std::shared_ptr<void> destinations;
  CommandLine line;
};
template <class Arguments>
[[nodiscard]] OwnedCommandLine owned_command_line(CommandLine (*command_line)(Arguments&)) {
  auto destinations = std::make_shared<Arguments>();
  CommandLine line = command_line(*destinations);
  return {std::move(destinations), std::move(line)};
}

// Reads `args` (the command line without the program and command names) as `line` says. Returns nothing when
// the command is to run; otherwise the exit status it ends with: exit_ok after --help printed the help
// (exit_usage when it could not be written), exit_usage after one of the messages above.
[[nodiscard]] std::optional<int> parse_command_line(const CommandLine& line, const std::vector<std::string>& args);

// The command's help: help_before; "options (how values are given):" and a row per option (its spellings,
// then its help wrapped in a column), --help and, for a command with an operand, --; help_after.
[[nodiscard]] std::string help_text(const CommandLine& line);

// ---- Values: the typed destinations of the tables ----------------------------------------------------------

// A flag: sets `destination` to `value` (--progress, --no-progress), or a bool to true. An action is a flag that
// ends the command line.
template <class T, class U>
[[nodiscard]] Value flag(T& destination, U value) {
  Value v;
  v.store = [&destination, value](const std::string&) {
    destination = value;
    return true;
  };
  return v;
}
[[nodiscard]] inline Value flag(bool& destination) { return flag(destination, true); }
[[nodiscard]] inline Value action(bool& destination) {
  Value v = flag(destination);
  v.ends_command_line = true;
  return v;
}

// A decimal integer from `min` to `max`: digits only (no sign, no blank, no exponent), into an unsigned
// integer or an optional one.
[[nodiscard]] std::optional<std::uint64_t> parse_integer(const std::string& text, std::uint64_t min, std::uint64_t max);
template <class T>
struct Stored {
  using type = T;
};
template <class T>
struct Stored<std::optional<T>> {
  using type = T;
};
// An integer value: its range for the help and the messages, and how the text is stored.
[[nodiscard]] inline Value integer_value(std::string metavar, std::string range,
                                         std::function<bool(const std::string&)> store) {
  Value v;
  v.takes = Value::Takes::value;
  v.metavar = std::move(metavar);
  v.range = std::move(range);
  v.accepts = "an integer from " + v.range;
  v.store = std::move(store);
  return v;
}
template <class T>
[[nodiscard]] Value integer(T& destination, std::uint64_t min, std::uint64_t max, std::string metavar = "N") {
  return integer_value(std::move(metavar), std::to_string(min) + " to " + std::to_string(max),
                       [&destination, min, max](const std::string& text) {
                         const std::optional<std::uint64_t> n = parse_integer(text, min, max);
                         if (n) destination = static_cast<typename Stored<T>::type>(*n);
                         return n.has_value();
                       });
}

// A decimal integer from `min` to `max` that may be negative: an optional '-', then digits only.
[[nodiscard]] inline Value signed_integer(std::int64_t& destination, std::int64_t min, std::int64_t max,
                                          std::string metavar = "N") {
  return integer_value(std::move(metavar), std::to_string(min) + " to " + std::to_string(max),
                       [&destination, min, max](const std::string& text) {
                         const bool negative = text.starts_with('-');
                         const std::uint64_t limit = negative ? static_cast<std::uint64_t>(-(min < 0 ? min : 0))
                                                              : static_cast<std::uint64_t>(max < 0 ? 0 : max);
                         const std::optional<std::uint64_t> n = parse_integer(negative ? text.substr(1) : text, 0, limit);
                         if (!n) return false;
                         const std::int64_t value =
                             negative ? -static_cast<std::int64_t>(*n) : static_cast<std::int64_t>(*n);
                         if (value < min || value > max) return false;
                         destination = value;
                         return true;
                       });
}

// One of the named choices ("owned", "closed"): the help shows owned|closed, messages "owned or closed".
template <class T>
using Choices = std::vector<std::pair<std::string, T>>;
[[nodiscard]] std::string choice_list(const std::vector<std::string>& names, std::string_view separator,
                                      std::string_view last_separator);
template <class T, class D>
[[nodiscard]] Value one_of(D& destination, const Choices<T>& choices) {
  std::vector<std::string> names;
  for (const auto& choice : choices) names.push_back(choice.first);
  Value v;
  v.takes = Value::Takes::value;
  v.metavar = choice_list(names, "|", "|");
  v.accepts = choice_list(names, ", ", " or ");
  v.store = [&destination, choices](const std::string& text) {
    for (const auto& [name, value] : choices)
      if (text == name) {
        destination = value;
        return true;
      }
    return false;
  };
  return v;
}

// A file name, not empty, into a std::string or an optional one ("-" means what the command makes of it; say
// so in `accepts`).
template <class D>
[[nodiscard]] Value file(D& destination, std::string metavar = "FILE", std::string accepts = "a file name") {
  Value v;
  v.takes = Value::Takes::value;
  v.metavar = std::move(metavar);
  v.accepts = std::move(accepts);
  v.store = [&destination](const std::string& path) {
    if (path.empty()) return false;
    destination = path;
    return true;
  };
  return v;
}

// `--name[=FILE]`: the file, or "" when it is left out (the command derives a name).
[[nodiscard]] Value optional_file(std::optional<std::string>& destination);

}  // namespace raykernel::cli
