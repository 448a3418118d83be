// The uampc command line's frame: one CLI11 app, a subcommand per command, help laid out with a
// synopsis per command, and the exit code 2 for every command-line error. Each command declares its
// own options beside what it does (add*Command in its folder); main.cpp only lists the commands.
#pragma once

#include <CLI/CLI.hpp>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace uampc::app {

inline constexpr int kCommandLineError = 2;  // also "bad scene": both mean nothing ran

// CLI11's help, laid out as uampc's always was: a synopsis per command ("uampc launch SCENE.yaml
// [--set NAME=VALUE ...] [--out DIR]") above its description, where CLI11 would print
// "Usage: uampc launch [OPTIONS] SCENE.yaml".
class SynopsisFormatter : public CLI::Formatter {
 public:
  // A line break in a synopsis continues it under its first argument.
  void addSynopsis(const std::string& command, const std::string& synopsis) { synopses_[command] = synopsis; }

  std::string make_help(const CLI::App* app, std::string name, CLI::AppFormatMode mode) const override;
  std::string make_usage(const CLI::App* app, std::string) const override;
  std::string make_subcommand(const CLI::App* sub) const override;

 private:
  std::string synopsis(const CLI::App& command, const std::string& prefix) const;
  std::map<std::string, std::string> synopses_;
};

class CommandSet {
 public:
  CommandSet();

  // A new command: its synopsis (for help and errors) and its description.
  CLI::App* add(const std::string& name, const std::string& synopsis, const std::string& description);
  // What runs when `command` was given; returns the exit code.
  void onRun(CLI::App* command, std::function<int()> run);
  // A synopsis for a nested subcommand (uampc topic echo, uampc security init).
  void addSynopsis(const std::string& name, const std::string& synopsis) { formatter_->addSynopsis(name, synopsis); }

  // "uampc launch: <message>", the command's synopsis and where to read more; exit code 2.
  int usageError(const CLI::App* command, const std::string& message) const;

  int run(int argc, char** argv);
  CLI::App& app() { return app_; }  // for what belongs to uampc as a whole (--version, the footer)

 private:
  struct Command {
    CLI::App* app;
    std::function<int()> run;
  };
  const Command* given() const;

  std::shared_ptr<SynopsisFormatter> formatter_ = std::make_shared<SynopsisFormatter>();
  CLI::App app_{"", "uampc"};
  std::vector<Command> commands_;
};

}  // namespace uampc::app
