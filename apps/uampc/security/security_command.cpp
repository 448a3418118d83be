#include "security/security_command.hpp"

#include <chrono>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <sstream>
#include <vector>

#include "cli/command_set.hpp"
#include "external_command.hpp"
#include "uampc/plots/svg_plot.hpp"  // svg::escapeXml
#include "uampc/run_files/text_file.hpp"
#include "uampc/runtime/dds_names.hpp"
#include "uampc/runtime/dds_security.hpp"
#include "uampc/runtime/process_group.hpp"
#include "uampc/runtime/scene.hpp"

namespace fs = std::filesystem;

namespace uampc::app {

namespace {

// openssl failed; what it said is in the message.
struct OpensslError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Runs `openssl ARGS` in `directory`, its output in a log that is shown when it fails.
void openssl(const fs::path& directory, const std::vector<std::string>& args) {
  std::vector<std::string> argv = {"openssl"};
  argv.insert(argv.end(), args.begin(), args.end());
  const ExternalCommandResult r = runExternalCommand(argv, (directory / "openssl.log").string());
  if (!r.started) {
    throw OpensslError("cannot run openssl (" + r.error +
                       "); install Debian's openssl package (docker/install-deps.sh does)");
  }
  if (!r.ok()) throw OpensslError(commandText(argv) + " failed:\n" + r.output);
}

// "2026-05-01T12:00:00", UTC, `days` from now (negative: before).
std::string isoTime(int days) {
  const std::time_t t = std::time(nullptr) + static_cast<std::time_t>(days) * 86400;
  std::tm utc{};
  gmtime_r(&t, &utc);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%S", &utc);
  return text;
}

// Every participant must authenticate (no unauthenticated participant joins), discovery and
// liveliness are encrypted, and on every topic only permitted participants read and write; the
// samples are encrypted and authenticated (AES-GCM): an outsider can neither read nor forge them.
// Signing the submessages around them too (heartbeats, acknowledgements: metadata SIGN) cost the
// three-process loop 29 % more CPU against 8 % without (docs/results/security-overhead.md), and
// only keeps an outsider from disturbing delivery, which flooding does anyway: it is an option.
std::string governanceXml(bool sign_metadata) {
  return R"(<?xml version="1.0" encoding="UTF-8"?>
<!-- uampc's DDS Security governance (uampc security init): every domain, every topic protected. -->
<dds xmlns:xsi="http://www.w3.org/2001/XMLSchema-instance"
     xsi:noNamespaceSchemaLocation="http://www.omg.org/spec/DDS-SECURITY/20170901/omg_shared_ca_governance.xsd">
  <domain_access_rules>
    <domain_rule>
      <domains><id_range><min>0</min><max>)" +
         std::to_string(kMaxDomainId) + R"(</max></id_range></domains>
      <allow_unauthenticated_participants>false</allow_unauthenticated_participants>
      <enable_join_access_control>true</enable_join_access_control>
      <discovery_protection_kind>ENCRYPT</discovery_protection_kind>
      <liveliness_protection_kind>ENCRYPT</liveliness_protection_kind>
      <rtps_protection_kind>NONE</rtps_protection_kind>
      <topic_access_rules>
        <topic_rule>
          <topic_expression>*</topic_expression>
          <enable_discovery_protection>true</enable_discovery_protection>
          <enable_liveliness_protection>true</enable_liveliness_protection>
          <enable_read_access_control>true</enable_read_access_control>
          <enable_write_access_control>true</enable_write_access_control>
          <metadata_protection_kind>)" +
         std::string(sign_metadata ? "SIGN" : "NONE") + R"(</metadata_protection_kind>
          <data_protection_kind>ENCRYPT</data_protection_kind>
        </topic_rule>
      </topic_access_rules>
    </domain_rule>
  </domain_access_rules>
</dds>
)";
}

std::string subjectName(const std::string& identity) { return "CN=" + identity + ",O=uampc"; }

std::string permissionsXml(const std::string& identity, const TopicGrant& grant, int days) {
  auto topics = [](const std::set<std::string>& names) {
    std::string out;
    for (const auto& n : names) out += "            <topic>" + svg::escapeXml(n) + "</topic>\n";
    return out;
  };
  std::string xml = R"(<?xml version="1.0" encoding="UTF-8"?>
<!-- uampc's DDS Security permissions of ')" +
                    identity + R"(' (uampc security init): only the topics its scene gives it. -->
<dds xmlns:xsi="http://www.w3.org/2001/XMLSchema-instance"
     xsi:noNamespaceSchemaLocation="http://www.omg.org/spec/DDS-SECURITY/20170901/omg_shared_ca_permissions.xsd">
  <permissions>
    <grant name=")" +
                    identity +
                    R"(">
      <subject_name>)" +
                    subjectName(identity) + R"(</subject_name>
      <validity>
        <not_before>)" +
                    isoTime(-1) + R"(</not_before>
        <not_after>)" +
                    isoTime(days) + R"(</not_after>
      </validity>
      <allow_rule>
        <domains><id_range><min>0</min><max>)" +
                    std::to_string(kMaxDomainId) + "</max></id_range></domains>\n";
  if (!grant.publish.empty())
    xml +=
        "        <publish>\n          <topics>\n" + topics(grant.publish) + "          </topics>\n        </publish>\n";
  if (!grant.subscribe.empty())
    xml += "        <subscribe>\n          <topics>\n" + topics(grant.subscribe) +
           "          </topics>\n        </subscribe>\n";
  xml += R"(      </allow_rule>
      <default>DENY</default>
    </grant>
  </permissions>
</dds>
)";
  return xml;
}

// The private keys are secrets: readable by their owner only.
void ownerOnly(const fs::path& file) {
  fs::permissions(file, fs::perms::owner_read | fs::perms::owner_write, fs::perm_options::replace);
}

// The folders hold the keys: nobody but their owner may replace files in them, whatever the umask
// (the runtime warns about such folders: docs/decisions/security-key-permissions.md).
void ownerWritesOnly(const fs::path& folder) {
  fs::permissions(folder, fs::perms::group_write | fs::perms::others_write, fs::perm_options::remove);
}

void makeCa(const fs::path& dir, int days) {
  openssl(dir, {"req", "-x509", "-newkey", "ec", "-pkeyopt", "ec_paramgen_curve:prime256v1", "-nodes", "-keyout",
                (dir / "ca.key.pem").string(), "-out", (dir / "ca.cert.pem").string(), "-days", std::to_string(days),
                "-subj", "/O=uampc/CN=uampc DDS Security CA"});
  ownerOnly(dir / "ca.key.pem");
}

void signDocument(const fs::path& dir, const fs::path& xml, const fs::path& signed_file) {
  openssl(dir, {"smime", "-sign", "-text", "-in", xml.string(), "-out", signed_file.string(), "-signer",
                (dir / "ca.cert.pem").string(), "-inkey", (dir / "ca.key.pem").string()});
}

void makeIdentity(const fs::path& dir, const std::string& identity, const TopicGrant& grant, int days, int serial) {
  const fs::path folder = identityFolder(dir.string(), identity);
  fs::create_directories(folder);
  ownerWritesOnly(folder);
  std::error_code ec;
  if (!fs::equivalent(folder.parent_path(), dir, ec)) ownerWritesOnly(folder.parent_path());  // processes/, tools/
  const fs::path request = folder / "cert.csr";
  openssl(dir, {"req", "-new", "-newkey", "ec", "-pkeyopt", "ec_paramgen_curve:prime256v1", "-nodes", "-keyout",
                (folder / "key.pem").string(), "-out", request.string(), "-subj", "/O=uampc/CN=" + identity});
  ownerOnly(folder / "key.pem");
  openssl(dir, {"x509", "-req", "-in", request.string(), "-CA", (dir / "ca.cert.pem").string(), "-CAkey",
                (dir / "ca.key.pem").string(), "-set_serial", std::to_string(serial), "-days", std::to_string(days),
                "-out", (folder / "cert.pem").string()});
  fs::remove(request);
  run_files::writeTextFile(folder / "permissions.xml", permissionsXml(identity, grant, days));
  signDocument(dir, folder / "permissions.xml", folder / "permissions.p7s");
}

}  // namespace

std::map<std::string, TopicGrant> topicGrants(const Scene& scene) {
  std::map<std::string, TopicGrant> grants;
  for (const auto& process : scene.processes()) {
    TopicGrant& grant = grants[process];
    grant.subscribe.insert(ddsTopicName(kClockTopic));
    // Processes that step themselves (clock.in_process): the first publishes /clock.
    if (scene.processesStepThemselves() && process == scene.processes().front())
      grant.publish.insert(ddsTopicName(kClockTopic));
    grant.publish.insert(ddsTopicName(kStepAckTopic));
    grant.subscribe.insert(ddsTopicName(kStepAckTopic));  // each process waits for the others' acknowledgements
    grant.publish.insert(ddsTopicName(kStepProgressTopic));
  }
  for (const auto& c : scene.components) {
    TopicGrant& grant = grants[c.process];
    for (const auto& port : c.ports) {
      const std::string topic = ddsTopicName(c.topics.at(port.name));
      (port.direction == PortDirection::kOutput ? grant.publish : grant.subscribe).insert(topic);
    }
  }
  TopicGrant& launcher = grants[kLauncherIdentity];
  launcher.publish.insert(ddsTopicName(kClockTopic));
  launcher.subscribe.insert(ddsTopicName(kStepAckTopic));
  launcher.subscribe.insert(ddsTopicName(kStepProgressTopic));
  launcher.publish.insert(ddsTopicName(kStepProgressTopic));  // its presence (lockstep_clock.cpp)
  grants[kObserverIdentity].subscribe.insert("*");
  grants[kPlayerIdentity].publish.insert("*");
  return grants;
}

int securityInitCommand(const SecurityInitOptions& options) {
  ComponentCatalog catalog;
  Scene scene;
  try {
    scene = loadScene(options.scene_path, {}, catalog, /*check_security=*/false);
  } catch (const SceneError& e) {
    for (const auto& m : e.messages()) std::cerr << m << "\n";
    std::cerr << "uampc security init: " << e.messages().size() << " error(s) in scene " << options.scene_path
              << "; nothing was written\n";
    return 2;
  }
  const fs::path dir = fs::absolute(options.directory).lexically_normal();
  std::error_code ec;
  if (fs::exists(dir / "ca.cert.pem", ec) || fs::exists(dir / "processes", ec)) {
    std::cerr << "uampc security init: " << dir.string()
              << " already holds a security directory; remove it or name another (nothing was written)\n";
    return 2;
  }
  const auto grants = topicGrants(scene);
  try {
    fs::create_directories(dir);
    ownerWritesOnly(dir);
    makeCa(dir, options.days);
    run_files::writeTextFile(dir / "governance.xml", governanceXml(options.sign_metadata));
    signDocument(dir, dir / "governance.xml", dir / "governance.p7s");
    int serial = 1;
    for (const auto& [identity, grant] : grants) makeIdentity(dir, identity, grant, options.days, ++serial);
  } catch (const std::exception& e) {
    std::cerr << "uampc security init: " << e.what() << "\n";
    return 1;
  }
  // What the runtime will check at load, checked now: a directory that would not run is no success.
  for (const auto& [identity, grant] : grants) {
    for (const auto& problem : checkSecurityIdentity(securityIdentity(dir.string(), identity))) {
      std::cerr << "uampc security init: " << problem << "\n";
      return 1;
    }
  }
  std::cout << "DDS Security for scene '" << scene.name << "' in " << dir.string() << " (valid " << options.days
            << " days):\n";
  for (const auto& [identity, grant] : grants) {
    std::cout << "  " << identityFolder(dir.string(), identity) << "\n    publish:  ";
    for (const auto& t : grant.publish) std::cout << " " << t;
    std::cout << "\n    subscribe:";
    for (const auto& t : grant.subscribe) std::cout << " " << t;
    std::cout << "\n";
  }
  std::cout << "Add to the scene:   security: {directory: " << dir.string() << "}\n"
            << "or run it with:     uampc launch SCENE.yaml --set 'security={directory: " << dir.string() << "}'\n"
            << "Tools beside it:    uampc topic|record ... --security " << dir.string()
            << " (reads every topic), uampc play ... --security " << dir.string() << " (publishes every topic)\n"
            << dir.string()
            << "/ca.key.pem signs identities and permissions: keep it away from the machines that run.\n";
  return 0;
}

void addSecurityCommand(CommandSet& commands) {
  auto options = std::make_shared<SecurityInitOptions>();
  SecurityInitOptions& o = *options;
  CLI::App* sub =
      commands.add("security", "uampc security init DIR --scene SCENE.yaml [--days N] [--sign-metadata]",
                   "DDS Security (authentication, encryption, permissions) for a scene's runs. 'init' makes\n"
                   "DIR with openssl: a CA, an identity per process of the scene and one for the launcher,\n"
                   "the governance and, per identity, permissions for exactly the topics its components read\n"
                   "and write, signed by the CA. Then run the scene with security: {directory: DIR}.");
  sub->require_subcommand(1);
  CLI::App* init = sub->add_subcommand("init", "Make the security directory DIR for a scene.");
  commands.addSynopsis("init", "uampc security init DIR --scene SCENE.yaml [--days N] [--sign-metadata]");
  init->add_option("DIR", o.directory, "The directory to make (must not hold one already).")->required()->type_name("");
  init->add_option("--scene", o.scene_path, "The scene whose processes and topics are granted.")
      ->required()
      ->type_name("SCENE.yaml");
  init->add_option("--days", o.days, "Validity of the certificates and permissions, days (default 365).")
      ->check(CLI::Range(1, 36500))
      ->type_name("N");
  init->add_flag("--sign-metadata", o.sign_metadata,
                 "Also sign every submessage around the samples (heartbeats, acknowledgements), so that an\n"
                 "outsider cannot disturb delivery; costs more CPU (docs/user/security.md, \"Cost\").");
  commands.onRun(sub, [options] { return securityInitCommand(*options); });
}

}  // namespace uampc::app
