// Unknown subcommands and options (see unknown_arguments.h).
#include "unknown_arguments.h"

#include <cctype>
#include <vector>

#include "closest_name.h"

namespace trackbed::apps {
namespace {

// An option's spelling as given: "--seed=3" → "--seed", "-j2" → "-j"; "" for
// anything else (a positional argument, a negative number).
std::string OptionName(const std::string& arg) {
  if (arg.size() < 2 || arg[0] != '-') return "";
  if (arg[1] == '-')
    return arg.size() > 2 && std::isalpha(static_cast<unsigned char>(arg[2]))
               ? arg.substr(0, arg.find('='))
               : "";
  return std::isalpha(static_cast<unsigned char>(arg[1])) ? arg.substr(0, 2) : "";
}

// Every spelling of `app`'s options ("--out", "-h", "--help"), and the option of each.
struct Spellings {
  std::vector<std::string> names;
  std::vector<const CLI::Option*> options;
};

Spellings OptionSpellings(const CLI::App& app) {
  Spellings s;
  for (const CLI::Option* o : app.get_options()) {
    for (const std::string& n : o->get_lnames()) {
      s.names.push_back("--" + n);
      s.options.push_back(o);
    }
    for (const std::string& n : o->get_snames()) {
      s.names.push_back("-" + n);
      s.options.push_back(o);
    }
  }
  return s;
}

std::string Answer(const std::string& who, const std::string& what, const std::string& word,
                   const std::vector<std::string>& valid) {
  std::string line = who + ": unknown " + what + " '" + word + "'";
  if (const std::optional<std::string> closest = ClosestName(word, valid))
    return line + "; did you mean '" + *closest + "'?";
  line += " (one of:";
  for (const std::string& v : valid) line += " " + v;
  return line + ")";
}

}  // namespace

std::optional<std::string> UnknownArgument(CLI::App& app, int argc, const char* const* argv) {
  const std::vector<CLI::App*> subs = app.get_subcommands([](CLI::App*) { return true; });
  std::vector<std::string> subcommands;
  for (const CLI::App* sub : subs) subcommands.push_back(sub->get_name());
  const CLI::App* current = &app;
  std::string who = "trackbed";
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--") break;
    const std::string name = OptionName(arg);
    if (name.empty()) {
      if (current != &app) continue;  // the subcommand's positional argument
      std::size_t s = 0;
      while (s < subs.size() && subcommands[s] != arg) ++s;
      if (s == subs.size()) return Answer(who, "subcommand", arg, subcommands);
      current = subs[s];
      who = "trackbed " + arg;
      continue;
    }
    const Spellings spellings = OptionSpellings(*current);
    std::size_t k = 0;
    while (k < spellings.names.size() && spellings.names[k] != name) ++k;
    if (k == spellings.names.size()) return Answer(who, "option", name, spellings.names);
    // A value in the next argument: skip it ("--offset -0.5", "--out -dir").
    if (arg == name && spellings.options[k]->get_type_size_max() > 0) ++i;
  }
  return std::nullopt;
}

}  // namespace trackbed::apps
