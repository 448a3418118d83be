// DDS Security for a scene's participants: Fast DDS's built-in plugins, PKI-DH
// authentication, Access-Permissions and AES-GCM-GMAC encryption, turned on by the scene's
// `security: {directory: DIR}`. DIR is what `uampc security init` writes: one CA (it signs the
// identities and, as permissions CA, the governance and permissions documents), and an identity
// per scene process plus one for the launcher's lockstep clock, each with its certificate, private
// key and permissions (docs/user/security.md).
#pragma once

#include <fastdds/dds/domain/qos/DomainParticipantQos.hpp>
#include <string>
#include <vector>

namespace uampc {

// The identity of the launcher's participant (the lockstep clock). Process names start with a
// letter, so no process can take it: the launcher's files live in DIR/launcher, a process's in
// DIR/processes/NAME.
inline constexpr const char* kLauncherIdentity = "launcher";
// The identities of uampc's tools beside a secured run (their files in DIR/tools/observer and
// DIR/tools/player). A hyphen keeps them apart from any process name. The observer may read every
// topic (uampc topic, uampc record); the player may publish every topic (uampc play): it can
// command the motor, so it is handed out like a process's key.
inline constexpr const char* kObserverIdentity = "uampc-observer";
inline constexpr const char* kPlayerIdentity = "uampc-player";

// The files one participant authenticates and is authorized with; all empty: security off.
struct DdsIdentity {
  std::string name;         // a process of the scene, or kLauncherIdentity
  std::string ca;           // identity CA and permissions CA certificate (PEM)
  std::string certificate;  // this identity's certificate (PEM), signed by the CA
  std::string private_key;  // its private key (PEM, unencrypted)
  std::string governance;   // the domain governance document, S/MIME signed by the CA
  std::string permissions;  // this identity's permissions document, S/MIME signed by the CA
  bool enabled() const { return !certificate.empty(); }
};

// Where an identity's files are in a security directory; security off (all empty) when
// `directory` is empty. `name` is a process name or kLauncherIdentity.
DdsIdentity securityIdentity(const std::string& directory, const std::string& name);
// The folder of an identity inside the directory (DIR/launcher, DIR/tools/observer,
// DIR/tools/player or DIR/processes/NAME).
std::string identityFolder(const std::string& directory, const std::string& name);

// Sets the participant properties that turn on the built-in plugins with these files; does
// nothing when the identity is not enabled.
void applyDdsSecurity(eprosima::fastdds::dds::DomainParticipantQos& qos, const DdsIdentity& identity);

// What is wrong with an identity's files, each message naming the file: missing or unreadable,
// a certificate expired, not yet valid or not issued by the CA, a key that does not match its
// certificate, a document not signed by the CA or past its validity. Empty when all is well.
// Fast DDS would only refuse to create the participant, without saying why.
std::vector<std::string> checkSecurityIdentity(const DdsIdentity& identity);

// What others than the owner could do with an identity's files: read its private key (any group or
// other permission bit, as ssh judges a key), or replace its files (a folder from the security
// directory down to the key writable by group or others). Each message names the file, its mode
// and the chmod that fixes it. Warnings, not problems: the run goes on
// (docs/decisions/security-key-permissions.md). Empty when all is well or a file is missing.
std::vector<std::string> securityPermissionWarnings(const DdsIdentity& identity);

// securityIdentity, checked: throws std::runtime_error with every problem checkSecurityIdentity
// finds, and writes securityPermissionWarnings to stderr. Security off (an empty identity) when
// directory is empty. For the tools' --security.
DdsIdentity checkedSecurityIdentity(const std::string& directory, const std::string& name);

}  // namespace uampc
