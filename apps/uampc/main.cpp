// The uampc command line: one CLI11 app with a subcommand per command. Each command declares its
// options beside what it does (add*Command in its folder; the frame is cli/command_set.hpp), so
// that `uampc --help` and `uampc COMMAND --help` print what the code next to the command says.
#include "bag/play_command.hpp"
#include "bag/record_command.hpp"
#include "calibrate/calibrate_command.hpp"
#include "cli/command_set.hpp"
#include "commands/components_command.hpp"
#include "commands/scene_commands.hpp"
#include "commands/version.hpp"
#include "experiment/experiment_command.hpp"
#include "security/security_command.hpp"
#include "topic/topic_command.hpp"
#include "view/view_command.hpp"

namespace {

const char* const kFooter =
    R"(Component libraries are searched in $UAMPC_COMPONENT_PATH (colon-separated), then next to this binary
in ../lib/uampc/components. Log level: UAMPC_LOG_LEVEL=debug|info|warn|error.
Exit codes: 0 success, 1 run failed, 2 bad scene or command line, 130 Ctrl-C.)";

}  // namespace

int main(int argc, char** argv) {
  using namespace uampc::app;
  CommandSet commands;
  commands.app().set_version_flag("--version", versionText,
                                  "Print uampc's version (git describe when it was built) and Fast DDS's, and exit");
  commands.app().footer(kFooter);
  addSceneCommands(commands);  // launch, validate, graph, run-process, clock
  addExperimentCommand(commands);
  addComponentsCommand(commands);
  addTopicCommand(commands);
  addRecordCommand(commands);
  addPlayCommand(commands);
  addCalibrateCommand(commands);
  addViewCommand(commands);
  addSecurityCommand(commands);
  return commands.run(argc, argv);
}
