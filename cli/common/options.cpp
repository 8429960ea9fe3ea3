#include "common/options.hpp"

#include "common/exit_status.hpp"
#include "common/io.hpp"
#include "common/text_format.hpp"

#include <algorithm>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

namespace raykernel::cli {
namespace {

// The options section of a help is wrapped to this many columns, as the hand-written prose around it is.
constexpr std::size_t help_width = 96;

// How the help shows an option: "-o, --output FILE", "--rule=owned|closed", "--show-stages[=FILE]". A list of
// choices is shown after '=' (--path certified|exact|naive would read as a pipe); other values after a blank.
std::string spelling(const Option& o) {
  std::string s = o.alias.empty() ? o.name : o.alias + ", " + o.name;
  switch (o.value.takes) {
    case Value::Takes::nothing: break;
    case Value::Takes::value:
      s += (o.value.metavar.find('|') != std::string::npos ? "=" : " ") + o.value.metavar;
      break;
    case Value::Takes::optional_value: s += "[=" + o.value.metavar + "]"; break;
  }
  return s;
}

// `text` wrapped into lines of at most help_width columns, the first after `first` (padded to `indent`
// columns), the others indented by `indent`.
std::string hanging(const std::string& first, std::size_t indent, const std::string& text) {
  std::string out = first;
  if (out.size() < indent) out.append(indent - out.size(), ' ');
  std::size_t column = out.size();
  bool line_start = true;
  std::istringstream words(text);
  for (std::string word; words >> word;) {
    if (!line_start && column + 1 + word.size() > help_width) {
      out += '\n';
      out.append(indent, ' ');
      column = indent;
      line_start = true;
    }
    if (!line_start) {
      out += ' ';
      ++column;
    }
    out += word;
    column += word.size();
    line_start = false;
  }
  return out + '\n';
}

// An option's help with the range of its integer: inside its closing parenthesis ("(default 1; 0 to 9)"), else
// in parentheses of its own.
std::string with_range(const std::string& help, const std::string& range) {
  if (range.empty()) return help;
  if (help.ends_with(')')) return help.substr(0, help.size() - 1) + "; " + range + ")";
  return help + " (" + range + ")";
}

// The row every command has.
Option help_option(bool& asked) { return Option("--help", "-h", action(asked), "this text"); }

const Option* find_option(const CommandLine& line, const Option& help, const std::string& name) {
  if (name == help.name || name == help.alias) return &help;
  for (const Option& o : line.options)
    if (o.name == name || (!o.alias.empty() && o.alias == name)) return &o;
  return nullptr;
}

}  // namespace

std::optional<int> parse_command_line(const CommandLine& line, const std::vector<std::string>& args) {
  const auto usage_error = [&line](const std::string& message) {
    std::cerr << "raykernel " << line.command << ": " << message << '\n';
    return exit_usage;
  };
  bool help_asked = false;
  const Option help = help_option(help_asked);
  std::vector<const Option*> given;  // the options that took a value
  bool options_ended = false;
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    if (options_ended || a == "-" || !a.starts_with('-')) {
      if (!line.operand)
        return usage_error("unexpected argument " + quote(a) + " (see raykernel " + line.command + " --help)");
      std::optional<std::string>& operand = *line.operand->destination;
      if (operand)
        return usage_error("more than one " + line.operand->what + " (" + quote(*operand, operand->size()) + ", " +
                           quote(a, a.size()) + ")");
      operand = a;
      continue;
    }
    if (a == "--") {
      options_ended = true;
      continue;
    }
    // A long option may carry its value after '='; an alias never does (-o=x is no option).
    const std::size_t equals = a.starts_with("--") ? a.find('=') : std::string::npos;
    const std::string name = a.substr(0, equals);
    const Option* option = find_option(line, help, name);
    if (!option) return usage_error("unknown option " + quote(a) + " (see raykernel " + line.command + " --help)");
    const Value::Takes takes = option->value.takes;
    std::string value;
    if (equals != std::string::npos) {
      if (takes == Value::Takes::nothing) return usage_error(name + " takes no value (" + quote(a) + ")");
      value = a.substr(equals + 1);
    } else if (takes == Value::Takes::value) {
      if (i + 1 >= args.size()) return usage_error(name + " needs a value (" + option->value.accepts + ")");
      value = args[++i];
    }
    if (takes != Value::Takes::nothing) {
      if (std::find(given.begin(), given.end(), option) != given.end()) return usage_error(name + " given twice");
      given.push_back(option);
    }
    if (!option->value.store(value))
      return usage_error("bad value for " + name + ": " + quote(value) + " (" + option->value.accepts + ")");
    if (help_asked) {
      std::cout << help_text(line);
      return finish_standard_output(exit_ok);
    }
    if (option->value.ends_command_line) return std::nullopt;
  }
  return std::nullopt;
}

std::string help_text(const CommandLine& line) {
  bool unused = false;
  const Option help = help_option(unused);
  std::vector<const Option*> rows;
  for (const Option& o : line.options) rows.push_back(&o);
  rows.push_back(&help);
  std::size_t column = 0;
  for (const Option* o : rows) column = std::max(column, spelling(*o).size());
  column += 2 + 3;  // the rows' indent, and the gap before the help

  // How values are given, in the heading: "options (a value as --name VALUE or --name=VALUE; [=FILE] only as
  // --name=FILE):".
  std::string heading = "options";
  const auto first_taking = [&line](Value::Takes t) {
    return std::find_if(line.options.begin(), line.options.end(), [t](const Option& o) { return o.value.takes == t; });
  };
  if (first_taking(Value::Takes::value) != line.options.end()) {
    heading += " (a value as --name VALUE or --name=VALUE";
    if (const auto o = first_taking(Value::Takes::optional_value); o != line.options.end())
      heading += "; [=" + o->value.metavar + "] only as --name=" + o->value.metavar;
    heading += ")";
  }
  std::string text = line.help_before + "\n" + heading + ":\n";
  for (const Option* o : rows) text += hanging("  " + spelling(*o), column, with_range(o->help, o->value.range));
  if (line.operand)
    text += hanging("  --", column, "end of options (" + line.operand->metavar + " may then start with -)");
  if (!line.help_after.empty()) text += "\n" + line.help_after;
  return text;
}

std::optional<std::uint64_t> parse_integer(const std::string& text, std::uint64_t min, std::uint64_t max) {
  if (text.empty() || text.find_first_not_of("0123456789") != std::string::npos) return std::nullopt;
  std::uint64_t v = 0;
  for (char c : text) {
    const auto digit = static_cast<std::uint64_t>(c - '0');
    if (v > (max - digit) / 10) return std::nullopt;  // v·10 + digit > max (and no wrap-around)
    v = v * 10 + digit;
  }
  if (v < min) return std::nullopt;
  return v;
}

std::string choice_list(const std::vector<std::string>& names, std::string_view separator,
                        std::string_view last_separator) {
  std::string list;
  for (std::size_t k = 0; k < names.size(); ++k) {
    if (k > 0) list += k + 1 == names.size() ? last_separator : separator;
    list += names[k];
  }
  return list;
}

Value optional_file(std::optional<std::string>& destination) {
  Value v;
  v.takes = Value::Takes::optional_value;
  v.metavar = "FILE";
  v.accepts = "a file name";
  v.store = [&destination](const std::string& path) {
    destination = path;
    return true;
  };
  return v;
}

}  // namespace raykernel::cli
