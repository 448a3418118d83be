#include "uampc/runtime/dds_security.hpp"

#include <openssl/bio.h>
#include <openssl/err.h>
#include <openssl/pem.h>
#include <openssl/pkcs7.h>
#include <openssl/x509.h>
#include <openssl/x509_vfy.h>

#include <ctime>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <regex>
#include <sstream>
#include <stdexcept>

#include "uampc/runtime/file_checks.hpp"

namespace fs = std::filesystem;

namespace uampc {

namespace {

template <typename T, void (*Free)(T*)>
struct Deleter {
  void operator()(T* p) const { Free(p); }
};
using Bio = std::unique_ptr<BIO, Deleter<BIO, BIO_free_all>>;
using Certificate = std::unique_ptr<X509, Deleter<X509, X509_free>>;
using Key = std::unique_ptr<EVP_PKEY, Deleter<EVP_PKEY, EVP_PKEY_free>>;
using Store = std::unique_ptr<X509_STORE, Deleter<X509_STORE, X509_STORE_free>>;
using StoreContext = std::unique_ptr<X509_STORE_CTX, Deleter<X509_STORE_CTX, X509_STORE_CTX_free>>;
using Pkcs7 = std::unique_ptr<PKCS7, Deleter<PKCS7, PKCS7_free>>;

// OpenSSL's last error as text, and the error queue emptied (so that one problem is said once).
std::string opensslError() {
  std::string text;
  for (unsigned long e; (e = ERR_get_error()) != 0;) {
    char buffer[256];
    ERR_error_string_n(e, buffer, sizeof buffer);
    if (text.empty()) text = buffer;
  }
  return text.empty() ? "unknown OpenSSL error" : text;
}

Certificate readCertificate(const std::string& file, std::vector<std::string>& problems) {
  Bio bio(BIO_new_file(file.c_str(), "r"));
  Certificate cert(bio ? PEM_read_bio_X509(bio.get(), nullptr, nullptr, nullptr) : nullptr);
  if (!cert) problems.push_back(file + ": not a PEM certificate (" + opensslError() + ")");
  return cert;
}

// Verifies `cert` against the CA alone, at the current time: expired, not yet valid and
// "issued by another CA" all come out of here with OpenSSL's words.
std::string verifyAgainst(X509_STORE* store, X509* cert) {
  StoreContext context(X509_STORE_CTX_new());
  if (!context || X509_STORE_CTX_init(context.get(), store, cert, nullptr) != 1) return opensslError();
  if (X509_verify_cert(context.get()) == 1) return {};
  return X509_verify_cert_error_string(X509_STORE_CTX_get_error(context.get()));
}

// The signed document's text when its S/MIME signature is the CA's; empty with a problem otherwise.
std::string verifiedDocument(const std::string& file, X509_STORE* store, std::vector<std::string>& problems) {
  Bio bio(BIO_new_file(file.c_str(), "r"));
  BIO* content = nullptr;
  Pkcs7 p7(bio ? SMIME_read_PKCS7(bio.get(), &content) : nullptr);
  Bio content_owner(content);
  if (!p7) {
    problems.push_back(file + ": not an S/MIME signed document (" + opensslError() + ")");
    return {};
  }
  Bio out(BIO_new(BIO_s_mem()));
  if (PKCS7_verify(p7.get(), nullptr, store, content, out.get(), PKCS7_TEXT) != 1) {
    problems.push_back(file + ": its signature is not the CA's or not valid (" + opensslError() + ")");
    return {};
  }
  char* data = nullptr;
  const long size = BIO_get_mem_data(out.get(), &data);
  return std::string(data, static_cast<std::size_t>(size));
}

// The permissions' validity (<not_after>2035-01-01T00:00:00</not_after>, UTC) against now.
void checkValidity(const std::string& file, const std::string& document, std::vector<std::string>& problems) {
  static const std::regex not_after("<not_after>\\s*([0-9]{4}-[0-9]{2}-[0-9]{2}T[0-9]{2}:[0-9]{2}:[0-9]{2})");
  std::smatch match;
  if (!std::regex_search(document, match, not_after)) return;  // Fast DDS says what it dislikes
  char now[32];
  const std::time_t t = std::time(nullptr);
  std::tm utc{};
  gmtime_r(&t, &utc);
  std::strftime(now, sizeof now, "%Y-%m-%dT%H:%M:%S", &utc);
  // The fixed-width ISO form orders as text orders.
  if (match[1].str() < now) problems.push_back(file + ": the permissions expired on " + match[1].str() + " (UTC)");
}

// A file's permission bits as chmod writes them ("0666"); nullopt when they cannot be read.
std::optional<std::string> modeText(const fs::path& path, fs::perms& perms) {
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  if (ec || !fs::exists(status)) return std::nullopt;
  perms = status.permissions() & fs::perms::mask;
  std::ostringstream text;
  text << '0' << std::oct << static_cast<unsigned>(perms & fs::perms::all);
  return text.str();
}

bool any(fs::perms perms, fs::perms bits) { return (perms & bits) != fs::perms::none; }

// ssh's rule for a private key: no permission bit for group or others.
void checkKeyMode(const fs::path& key, std::vector<std::string>& warnings) {
  fs::perms perms{};
  const auto mode = modeText(key, perms);
  if (!mode || !any(perms, fs::perms::group_all | fs::perms::others_all)) return;
  warnings.push_back(key.string() + ": a private key with mode " + *mode +
                     ", open to others than its owner (they could act as this identity on the domain); "
                     "fix: chmod 600 " + key.string());
}

// The folders from the key's up to the security directory: who may write in one may replace the
// key, the certificates and the permissions in it.
void checkFolderModes(const fs::path& root, const fs::path& key, std::vector<std::string>& warnings) {
  const fs::path top = root.lexically_normal();
  for (fs::path folder = key.parent_path().lexically_normal(); !folder.empty(); folder = folder.parent_path()) {
    fs::perms perms{};
    const auto mode = modeText(folder, perms);
    if (mode && any(perms, fs::perms::group_write | fs::perms::others_write)) {
      warnings.push_back(folder.string() + ": a folder of the security directory with mode " + *mode +
                         ", writable by others than its owner (they could replace its keys and certificates); "
                         "fix: chmod go-w " + folder.string());
    }
    if (folder == top || folder == folder.parent_path()) break;
  }
}

}  // namespace

std::vector<std::string> securityPermissionWarnings(const DdsIdentity& identity) {
  std::vector<std::string> warnings;
  if (!identity.enabled()) return warnings;
  checkKeyMode(identity.private_key, warnings);
  checkFolderModes(fs::path(identity.ca).parent_path(), identity.private_key, warnings);
  return warnings;
}

std::string identityFolder(const std::string& directory, const std::string& name) {
  const fs::path root(directory);
  if (name == kLauncherIdentity) return (root / "launcher").string();
  if (name == kObserverIdentity) return (root / "tools" / "observer").string();
  if (name == kPlayerIdentity) return (root / "tools" / "player").string();
  return (root / "processes" / name).string();
}

DdsIdentity securityIdentity(const std::string& directory, const std::string& name) {
  if (directory.empty()) return {};
  const fs::path root(directory);
  const fs::path folder(identityFolder(directory, name));
  return DdsIdentity{name,
                     (root / "ca.cert.pem").string(),
                     (folder / "cert.pem").string(),
                     (folder / "key.pem").string(),
                     (root / "governance.p7s").string(),
                     (folder / "permissions.p7s").string()};
}

void applyDdsSecurity(eprosima::fastdds::dds::DomainParticipantQos& qos, const DdsIdentity& identity) {
  if (!identity.enabled()) return;
  auto& properties = qos.properties().properties();
  auto set = [&](const std::string& name, const std::string& value) { properties.emplace_back(name, value); };
  set("dds.sec.auth.plugin", "builtin.PKI-DH");
  set("dds.sec.auth.builtin.PKI-DH.identity_ca", "file://" + identity.ca);
  set("dds.sec.auth.builtin.PKI-DH.identity_certificate", "file://" + identity.certificate);
  set("dds.sec.auth.builtin.PKI-DH.private_key", "file://" + identity.private_key);
  set("dds.sec.access.plugin", "builtin.Access-Permissions");
  set("dds.sec.access.builtin.Access-Permissions.permissions_ca", "file://" + identity.ca);
  set("dds.sec.access.builtin.Access-Permissions.governance", "file://" + identity.governance);
  set("dds.sec.access.builtin.Access-Permissions.permissions", "file://" + identity.permissions);
  set("dds.sec.crypto.plugin", "builtin.AES-GCM-GMAC");
}

std::vector<std::string> checkSecurityIdentity(const DdsIdentity& identity) {
  std::vector<std::string> problems;
  for (const std::string* file :
       {&identity.ca, &identity.certificate, &identity.private_key, &identity.governance, &identity.permissions}) {
    if (!isRegularFile(*file)) problems.push_back(*file + ": file not found");
  }
  if (!problems.empty()) return problems;

  ERR_clear_error();
  const Certificate ca = readCertificate(identity.ca, problems);
  const Certificate cert = readCertificate(identity.certificate, problems);
  if (!ca || !cert) return problems;
  Store store(X509_STORE_new());
  X509_STORE_add_cert(store.get(), ca.get());
  if (const std::string error = verifyAgainst(store.get(), ca.get()); !error.empty()) {
    problems.push_back(identity.ca + ": the CA certificate is not valid: " + error);
    return problems;
  }
  if (const std::string error = verifyAgainst(store.get(), cert.get()); !error.empty()) {
    problems.push_back(identity.certificate + ": " + error + " (checked against the CA " + identity.ca + ")");
  }
  {
    Bio bio(BIO_new_file(identity.private_key.c_str(), "r"));
    Key key(bio ? PEM_read_bio_PrivateKey(bio.get(), nullptr, nullptr, nullptr) : nullptr);
    if (!key) {
      problems.push_back(identity.private_key + ": not an unencrypted PEM private key (" + opensslError() + ")");
    } else if (X509_check_private_key(cert.get(), key.get()) != 1) {
      ERR_clear_error();
      problems.push_back(identity.private_key + ": this key does not belong to the certificate " +
                         identity.certificate);
    }
  }
  verifiedDocument(identity.governance, store.get(), problems);
  const std::string permissions = verifiedDocument(identity.permissions, store.get(), problems);
  if (!permissions.empty()) checkValidity(identity.permissions, permissions, problems);
  return problems;
}

DdsIdentity checkedSecurityIdentity(const std::string& directory, const std::string& name) {
  const DdsIdentity identity = securityIdentity(directory, name);
  if (!identity.enabled()) return identity;
  const std::vector<std::string> problems = checkSecurityIdentity(identity);
  if (problems.empty()) {
    for (const auto& w : securityPermissionWarnings(identity)) std::cerr << "warning: security: " << w << "\n";
    return identity;
  }
  std::string text = "security directory " + directory + ", identity " + name + ":";
  for (const auto& p : problems) text += "\n  " + p;
  throw std::runtime_error(text);
}

}  // namespace uampc
