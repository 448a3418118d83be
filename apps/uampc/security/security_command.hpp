// `uampc security init DIR --scene SCENE.yaml`: makes the DDS Security directory a scene's
// `security: {directory: DIR}` names (dds_security.hpp), with Debian's openssl command: one CA,
// an identity (certificate and private key) per scene process and one for the launcher's clock,
// the governance document and a permissions document per identity, signed (S/MIME) by the CA.
// Each process is granted exactly the topics its components read and write.
#pragma once

#include "cli/command_set.hpp"

#include <map>
#include <set>
#include <string>

namespace uampc {
struct Scene;
}

namespace uampc::app {

struct SecurityInitOptions {
  std::string directory;
  std::string scene_path;
  int days = 365;              // validity of the certificates and permissions
  bool sign_metadata = false;  // sign every submessage (metadata_protection_kind SIGN), not only the samples
};

// DDS topic names (rt/...) one identity may publish and subscribe to.
struct TopicGrant {
  std::set<std::string> publish;
  std::set<std::string> subscribe;
};

// Every identity the scene's run needs (its processes and kLauncherIdentity) with its topics: a
// process's components' outputs and inputs, and the lockstep clock's /clock and step
// acknowledgements (granted whatever the scene's clock mode, so that --set clock.mode works);
// and uampc's tools beside the run: kObserverIdentity reads every topic, kPlayerIdentity
// publishes every topic (the pattern "*").
std::map<std::string, TopicGrant> topicGrants(const Scene& scene);

// Exit codes: 0 done, 1 openssl failed or DIR cannot be written, 2 bad scene or DIR already used.
int securityInitCommand(const SecurityInitOptions& options);

// `uampc security init` and its options.
void addSecurityCommand(CommandSet& commands);

}  // namespace uampc::app
