#include "cli/command_set.hpp"

#include <iostream>

namespace uampc::app {

namespace {

std::string indented(const std::string& text, const std::string& indent) {
  return indent + CLI::detail::find_and_replace(text, "\n", "\n" + indent);
}

}  // namespace

std::string SynopsisFormatter::make_help(const CLI::App* app, std::string name, CLI::AppFormatMode mode) const {
  if (mode == CLI::AppFormatMode::Sub) return make_expanded(app);
  return make_usage(app, name) + make_description(app) + make_positionals(app) + make_groups(app, mode) +
         make_subcommands(app, mode) + "\n" + make_footer(app);
}

std::string SynopsisFormatter::make_usage(const CLI::App* app, std::string) const {
  if (app->get_parent() == nullptr) {
    return "usage: uampc COMMAND ...   (uampc COMMAND --help describes a command and its options)\n";
  }
  return "usage: " + synopsis(*app, "usage: ") + "\n";
}

std::string SynopsisFormatter::make_subcommand(const CLI::App* sub) const {
  return "  " + synopsis(*sub, "  ") + "\n" + indented(sub->get_description(), "      ") + "\n";
}

std::string SynopsisFormatter::synopsis(const CLI::App& command, const std::string& prefix) const {
  const auto found = synopses_.find(command.get_name());
  const std::string text = found == synopses_.end() ? "uampc " + command.get_name() : found->second;
  const std::string continuation = "\n" + std::string(prefix.size() + command.get_name().size() + 7, ' ');
  return CLI::detail::find_and_replace(text, "\n", continuation);
}

CommandSet::CommandSet() {
  app_.formatter(formatter_);  // before the subcommands: they copy their parent's formatter
  app_.set_help_flag("-h,--help", "Print this help and exit");
  app_.require_subcommand(1);
}

CLI::App* CommandSet::add(const std::string& name, const std::string& synopsis, const std::string& description) {
  formatter_->addSynopsis(name, synopsis);
  CLI::App* sub = app_.add_subcommand(name, description);
  sub->group("Commands");
  return sub;
}

void CommandSet::onRun(CLI::App* command, std::function<int()> run) { commands_.push_back({command, std::move(run)}); }

int CommandSet::run(int argc, char** argv) {
  if (argc < 2) {
    std::cout << app_.help();
    return kCommandLineError;
  }
  // CLI11 would say "A subcommand is required"; name what it got instead.
  const std::string first = argv[1];
  bool known = app_.get_option_no_throw(first) != nullptr;
  for (const Command& c : commands_) known = known || c.app->get_name() == first;
  if (!known) {
    return usageError(nullptr, (first.rfind('-', 0) == 0 ? "unknown option '" : "unknown command '") + first + "'");
  }
  try {
    app_.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == static_cast<int>(CLI::ExitCodes::Success)) return app_.exit(e);  // --help, --version
    const Command* command = given();
    return usageError(command ? command->app : nullptr, e.what());
  }
  const Command* command = given();
  return command ? command->run() : usageError(nullptr, "no command given");
}

int CommandSet::usageError(const CLI::App* command, const std::string& message) const {
  const std::string name = command ? "uampc " + command->get_name() : "uampc";
  std::cerr << name << ": " << message << "\n";
  if (command) std::cerr << formatter_->make_usage(command, "");
  std::cerr << "(" << name << " --help for more)\n";
  return kCommandLineError;
}

// The command on the command line, if CLI11 got as far as reading it.
const CommandSet::Command* CommandSet::given() const {
  for (const Command& c : commands_) {
    if (c.app->parsed()) return &c;
  }
  return nullptr;
}

}  // namespace uampc::app
