// Every command's command line, read by the one parse loop (cli/common/options.hpp): the tests go through the
// option table of every command (cli::commands()), so that an option added to a table is covered without a
// test of its own: both spellings of every value, the message for each kind of mistake, the generated --help.
#include "commands/commands.hpp"
#include "common/exit_status.hpp"
#include "common/options.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <sys/wait.h>

namespace raykernel::cli {
namespace {

// One parse of `args` by a command's table: the status, what went to stdout and stderr, each value an option
// stored (option name, value), and the operand.
struct Parse {
  std::optional<int> status;
  std::string out, err;
  std::vector<std::pair<std::string, std::string>> stored;
  std::optional<std::string> operand;
};

Parse parse(const Command& command, const std::vector<std::string>& args) {
  Parse p;
  OwnedCommandLine owned = command.command_line();
  for (Option& o : owned.line.options)
    o.value.store = [&p, name = o.name, store = o.value.store](const std::string& value) {
      p.stored.emplace_back(name, value);
      return store(value);
    };
  std::ostringstream out, err;
  std::streambuf* const cout_buffer = std::cout.rdbuf(out.rdbuf());
  std::streambuf* const cerr_buffer = std::cerr.rdbuf(err.rdbuf());
  p.status = parse_command_line(owned.line, args);
  std::cout.rdbuf(cout_buffer);
  std::cerr.rdbuf(cerr_buffer);
  p.out = out.str();
  p.err = err.str();
  if (owned.line.operand) p.operand = *owned.line.operand->destination;
  return p;
}

std::string prefix(const Command& c) { return "raykernel " + std::string(c.name) + ": "; }

// A value the option's store accepts: the lower end of its range, one of its choices, or a file name (a new
// kind of value that takes none of these fails the test: add a candidate here).
std::optional<std::string> valid_value(const Option& option) {
  std::vector<std::string> candidates;
  if (!option.value.range.empty()) candidates.push_back(option.value.range.substr(0, option.value.range.find(' ')));
  std::istringstream choices(option.value.metavar);
  for (std::string choice; std::getline(choices, choice, '|');) candidates.push_back(choice);
  candidates.emplace_back("some-file.txt");
  for (const std::string& v : candidates)
    if (option.value.store(v)) return v;
  return std::nullopt;
}

// Every option of every command, with its command (and the destinations its store writes to, which
// valid_value calls).
struct Row {
  const Command* command;
  Option option;
  std::shared_ptr<void> destinations;
};
std::vector<Row> every_option() {
  std::vector<Row> rows;
  for (const Command& c : commands()) {
    const OwnedCommandLine owned = c.command_line();
    for (const Option& o : owned.line.options) rows.push_back({&c, o, owned.destinations});
  }
  return rows;
}

TEST(Options, TheTablesHaveEveryKindOfOption) {
  int kinds[3] = {};
  for (const Row& r : every_option()) ++kinds[static_cast<int>(r.option.value.takes)];
  EXPECT_GT(kinds[static_cast<int>(Value::Takes::nothing)], 0);
  EXPECT_GT(kinds[static_cast<int>(Value::Takes::value)], 0);
  EXPECT_GT(kinds[static_cast<int>(Value::Takes::optional_value)], 0);
}

TEST(Options, EveryValueIsTakenInBothSpellings) {
  int checked = 0;
  for (const auto& [command, option, destinations] : every_option()) {
    if (option.value.takes != Value::Takes::value) continue;
    const std::string where = std::string(command->name) + " " + option.name;
    const std::optional<std::string> v = valid_value(option);
    ASSERT_TRUE(v) << where << ": no value of the test's candidates is valid";
    std::vector<std::vector<std::string>> spellings = {{option.name, *v}, {option.name + "=" + *v}};
    if (!option.alias.empty()) spellings.push_back({option.alias, *v});
    for (const std::vector<std::string>& args : spellings) {
      const Parse p = parse(*command, args);
      EXPECT_EQ(p.status, std::nullopt) << where << ": " << p.err;
      EXPECT_EQ(p.err, "") << where;
      EXPECT_EQ(p.stored, (std::vector<std::pair<std::string, std::string>>{{option.name, *v}})) << where;
      EXPECT_EQ(p.operand, std::nullopt) << where << ": the value is not an operand";
    }
    // A value is taken as it is, even when it starts with '-' (the parse stores it; the option may refuse it).
    const Parse dash = parse(*command, {option.name, "-"});
    ASSERT_FALSE(dash.stored.empty()) << where;
    EXPECT_EQ(dash.stored[0].second, "-") << where;
    ++checked;
  }
  EXPECT_GE(checked, 18);  // the value options of the tables when this test was written
}

TEST(Options, AnOptionalValueIsTakenOnlyAfterTheEqualsSign) {
  for (const auto& [command, option, destinations] : every_option()) {
    if (option.value.takes != Value::Takes::optional_value) continue;
    const std::string where = std::string(command->name) + " " + option.name;
    Parse p = parse(*command, {option.name + "=x.png"});
    EXPECT_EQ(p.status, std::nullopt) << where << ": " << p.err;
    EXPECT_EQ(p.stored, (std::vector<std::pair<std::string, std::string>>{{option.name, "x.png"}})) << where;
    // Left out: stored as "", and the next argument stays an operand.
    p = parse(*command, {option.name, "x.json"});
    EXPECT_EQ(p.status, std::nullopt) << where << ": " << p.err;
    EXPECT_EQ(p.stored, (std::vector<std::pair<std::string, std::string>>{{option.name, ""}})) << where;
    EXPECT_EQ(p.operand, "x.json") << where;
  }
}

TEST(Options, AFlagTakesNoValue) {
  for (const auto& [command, option, destinations] : every_option()) {
    if (option.value.takes != Value::Takes::nothing) continue;
    const std::string where = std::string(command->name) + " " + option.name;
    Parse p = parse(*command, {option.name});
    EXPECT_EQ(p.status, std::nullopt) << where << ": " << p.err;
    EXPECT_EQ(p.stored, (std::vector<std::pair<std::string, std::string>>{{option.name, ""}})) << where;
    p = parse(*command, {option.name + "=1"});
    EXPECT_EQ(p.status, exit_usage) << where;
    EXPECT_EQ(p.err, prefix(*command) + option.name + " takes no value ('" + option.name + "=1')\n") << where;
    EXPECT_TRUE(p.stored.empty()) << where;
  }
}

TEST(Options, AMissingValueIsOneMessage) {
  for (const auto& [command, option, destinations] : every_option()) {
    if (option.value.takes != Value::Takes::value) continue;
    const std::string where = std::string(command->name) + " " + option.name;
    for (const std::string& spelling : {option.name, option.alias}) {
      if (spelling.empty()) continue;
      const Parse p = parse(*command, {spelling});
      EXPECT_EQ(p.status, exit_usage) << where;
      EXPECT_EQ(p.err, prefix(*command) + spelling + " needs a value (" + option.value.accepts + ")\n") << where;
    }
  }
}

TEST(Options, AnEmptyValueIsABadValue) {
  // No kind of value takes "" (a file name is not empty either).
  for (const auto& [command, option, destinations] : every_option()) {
    if (option.value.takes != Value::Takes::value) continue;
    const std::string where = std::string(command->name) + " " + option.name;
    for (const std::vector<std::string>& args :
         {std::vector<std::string>{option.name + "="}, std::vector<std::string>{option.name, ""}}) {
      const Parse p = parse(*command, args);
      EXPECT_EQ(p.status, exit_usage) << where;
      EXPECT_EQ(p.err, prefix(*command) + "bad value for " + option.name + ": '' (" + option.value.accepts + ")\n")
          << where;
    }
  }
}

TEST(Options, AValueGivenTwiceIsOneMessage) {
  for (const auto& [command, option, destinations] : every_option()) {
    if (option.value.takes == Value::Takes::nothing) continue;
    const std::string where = std::string(command->name) + " " + option.name;
    const std::string v = option.value.takes == Value::Takes::value ? *valid_value(option) : "x.png";
    const Parse p = parse(*command, {option.name + "=" + v, option.name + "=" + v});
    EXPECT_EQ(p.status, exit_usage) << where;
    EXPECT_EQ(p.err, prefix(*command) + option.name + " given twice\n") << where;
  }
  // The alias and the name are one option.
  const Parse p = parse(*std::ranges::find(commands(), "render", &Command::name), {"-o", "a.png", "--output=b.png"});
  EXPECT_EQ(p.err, "raykernel render: --output given twice\n");
}

TEST(Options, OutOfRangeIsABadValue) {
  for (const auto& [command, option, destinations] : every_option()) {
    if (option.value.range.empty()) continue;
    const std::string where = std::string(command->name) + " " + option.name;
    const std::string max = option.value.range.substr(option.value.range.rfind(' ') + 1);
    const std::string min = option.value.range.substr(0, option.value.range.find(' '));
    // The magnitude + 1, written out (max may be 2^64 − 1): the last digit raised, carrying.
    const auto raised = [](std::string digits) {
      for (std::size_t k = digits.size(); k-- > 0;) {
        if (digits[k] != '9') {
          ++digits[k];
          break;
        }
        digits[k] = '0';
        if (k == 0) digits.insert(0, "1");
      }
      return digits;
    };
    const std::string above = raised(max);
    // Below the range: −1 for an unsigned range, min − 1 for a signed one (signed_integer).
    const std::string below = min.starts_with('-') ? "-" + raised(min.substr(1)) : std::string("-1");
    for (const std::string& bad :
         {above, below, std::string("+1"), std::string("1e3"), std::string(" 1")}) {
      const Parse p = parse(*command, {option.name, bad});
      EXPECT_EQ(p.status, exit_usage) << where << " " << bad;
      EXPECT_EQ(p.err, prefix(*command) + "bad value for " + option.name + ": '" + bad + "' (an integer from " +
                           option.value.range + ")\n")
          << where;
    }
    EXPECT_EQ(parse(*command, {option.name, max}).status, std::nullopt) << where;
  }
}

TEST(Options, AnUnknownOptionIsOneMessageForEveryCommand) {
  for (const Command& c : commands())
    for (const std::string unknown : {"--no-such-option", "--no-such-option=1", "-x", "-o=x", "--help-me"}) {
      const Parse p = parse(c, {unknown});
      EXPECT_EQ(p.status, exit_usage) << c.name << " " << unknown;
      EXPECT_EQ(p.err,
                prefix(c) + "unknown option '" + unknown + "' (see raykernel " + std::string(c.name) + " --help)\n")
          << c.name;
    }
}

TEST(Options, DoubleDashEndsTheOptionsAndDashIsAnOperand) {
  for (const Command& c : commands()) {
    OwnedCommandLine owned = c.command_line();
    if (!owned.line.operand) {
      for (const std::string operand : {"x", "-"}) {
        const Parse p = parse(c, {"--", operand});
        EXPECT_EQ(p.err, prefix(c) + "unexpected argument '" + operand + "' (see raykernel " + std::string(c.name) +
                             " --help)\n");
      }
      continue;
    }
    EXPECT_EQ(parse(c, {"-"}).operand, "-") << c.name;
    const Parse p = parse(c, {"--", "--help"});
    EXPECT_EQ(p.status, std::nullopt) << c.name << ": " << p.err;
    EXPECT_EQ(p.operand, "--help") << c.name;
    EXPECT_EQ(p.out, "") << c.name;
  }
}

// `text` with every run of blanks and newlines made one space.
std::string words(const std::string& text) {
  std::istringstream in(text);
  std::string out;
  for (std::string word; in >> word;) out += (out.empty() ? "" : " ") + word;
  return out;
}

TEST(Help, EveryOptionOfTheTableHasARowAndEveryCommandAnswersHelpAndH) {
  for (const Command& c : commands()) {
    const OwnedCommandLine owned = c.command_line();
    const std::string help = help_text(owned.line);
    for (const Option& o : owned.line.options) {
      EXPECT_NE(help.find("\n  " + (o.alias.empty() ? "" : o.alias + ", ") + o.name), std::string::npos)
          << c.name << " " << o.name;
      // The help of the row, wrapped (an integer's range closes it: all but its last character).
      EXPECT_NE(words(help).find(words(o.help.substr(0, o.help.size() - 1))), std::string::npos)
          << c.name << " " << o.name;
    }
    EXPECT_NE(help.find("\n  -h, --help "), std::string::npos) << c.name;
    EXPECT_EQ(help.find("\n  -- ") != std::string::npos, owned.line.operand.has_value()) << c.name;
    for (const std::string asked : {"--help", "-h"}) {
      const Parse p = parse(c, {asked, "--no-such-option"});  // the help ends the command line
      EXPECT_EQ(p.status, exit_ok) << c.name;
      EXPECT_EQ(p.out, help) << c.name;
      EXPECT_EQ(p.err, "") << c.name;
    }
  }
}

// The standard output of the binary with `args`, when it exits with 0.
std::string binary_output(const std::string& args) {
  FILE* pipe = popen((std::string(RAYKERNEL_CLI_PATH) + " " + args).c_str(), "r");
  if (!pipe) return "popen failed";
  std::string out;
  char buffer[4096];
  for (std::size_t n; (n = fread(buffer, 1, sizeof buffer, pipe)) > 0;) out.append(buffer, n);
  const int status = pclose(pipe);
  return WIFEXITED(status) && WEXITSTATUS(status) == 0 ? out : "exit status " + std::to_string(status);
}

// The binary prints the help of the table, and its overview lists every command.
TEST(Help, TheBinaryPrintsTheTablesHelpAndListsEveryCommand) {
  const std::string overview = binary_output("--help");
  for (const Command& c : commands()) {
    EXPECT_EQ(binary_output(std::string(c.name) + " --help"), help_text(c.command_line().line)) << c.name;
    EXPECT_NE(overview.find("\n  " + std::string(c.name) + " "), std::string::npos) << c.name;
  }
}

}  // namespace
}  // namespace raykernel::cli
