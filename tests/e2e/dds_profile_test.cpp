// A scene's dds_profile takes effect: the transports a Fast DDS profile names are the ones a
// participant opens (the profile's transports, segment size and security files used to be
// ignored). Each case makes its participant in a child process, because Fast DDS keeps the
// profiles it has loaded for the life of the process.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>

#include "command_runner.hpp"
#include "test_domains.hpp"
#include "uampc/runtime/dds_node.hpp"

namespace uampc::test {
namespace {

// Inodes of this process's open sockets.
std::set<std::string> ownSocketInodes() {
  std::set<std::string> inodes;
  for (const auto& fd : std::filesystem::directory_iterator("/proc/self/fd")) {
    std::error_code ec;
    const std::string target = std::filesystem::read_symlink(fd.path(), ec).string();
    if (!ec && target.rfind("socket:[", 0) == 0) inodes.insert(target.substr(8, target.size() - 9));
  }
  return inodes;
}

// How many of this process's sockets are UDP (IPv4 or IPv6), from /proc/net/udp*: inode is the
// tenth column.
int ownUdpSockets() {
  const std::set<std::string> own = ownSocketInodes();
  int count = 0;
  for (const char* table : {"/proc/net/udp", "/proc/net/udp6"}) {
    std::ifstream in(table);
    std::string line;
    std::getline(in, line);  // header
    while (std::getline(in, line)) {
      std::istringstream fields(line);
      std::string field;
      for (int i = 0; i < 10; ++i) fields >> field;
      count += own.count(field) ? 1 : 0;
    }
  }
  return count;
}

// The largest Fast DDS shared-memory segment this process has mapped, in bytes (0: none).
long largestSharedMemorySegment() {
  std::ifstream maps("/proc/self/maps");
  std::string line;
  long largest = 0;
  while (std::getline(maps, line)) {
    if (line.find("/dev/shm/fastrtps_") == std::string::npos) continue;
    const auto dash = line.find('-'), space = line.find(' ');
    const long size =
        std::stol(line.substr(dash + 1, space - dash - 1), nullptr, 16) - std::stol(line.substr(0, dash), nullptr, 16);
    largest = std::max(largest, size);
  }
  return largest;
}

struct Transports {
  int udp_sockets = -1;
  long largest_segment = -1;
  bool failed = false;
};

// Makes a participant with the profile in a child process and reports what it opened.
Transports openedWith(const std::string& profile, int domain) {
  int pipe_ends[2];
  if (pipe(pipe_ends) != 0) return {};
  const pid_t child = fork();
  if (child == 0) {
    close(pipe_ends[0]);
    Transports seen;
    try {
      DdsNode node(domain, profile, true, "dds_profile_test");
      seen.udp_sockets = ownUdpSockets();
      seen.largest_segment = largestSharedMemorySegment();
    } catch (const std::exception&) {
      seen.failed = true;
    }
    const ssize_t written = write(pipe_ends[1], &seen, sizeof seen);
    _exit(written == sizeof seen ? 0 : 1);
  }
  close(pipe_ends[1]);
  Transports seen;
  const ssize_t got = read(pipe_ends[0], &seen, sizeof seen);
  close(pipe_ends[0]);
  int status = 0;
  waitpid(child, &status, 0);
  EXPECT_EQ(got, static_cast<ssize_t>(sizeof seen));
  return seen;
}

std::string profileWith(const std::string& name, const std::string& transports_xml, const std::string& ids_xml) {
  const std::string path = freshDirectory("dds_profile_" + name) + "/" + name + ".xml";
  std::ofstream(path) << "<?xml version=\"1.0\" encoding=\"UTF-8\" ?>\n"
                         "<dds xmlns=\"http://www.eprosima.com/XMLSchemas/fastRTPS_Profiles\"><profiles>\n"
                         "<transport_descriptors>"
                      << transports_xml
                      << "</transport_descriptors>\n"
                         "<participant profile_name=\""
                      << name << "\" is_default_profile=\"true\"><rtps><userTransports>" << ids_xml
                      << "</userTransports><useBuiltinTransports>false</useBuiltinTransports></rtps></participant>\n"
                         "</profiles></dds>\n";
  return path;
}

const std::string kShm =
    "<transport_descriptor><transport_id>shm</transport_id><type>SHM</type></transport_descriptor>";
const std::string kUdp =
    "<transport_descriptor><transport_id>udp</transport_id><type>UDPv4</type></transport_descriptor>";

TEST(DdsProfile, WithoutAProfileBothBuiltinTransportsOpen) {
  const Transports seen = openedWith("", testDomain(DomainBlock::kDdsProfile, 0));
  ASSERT_FALSE(seen.failed);
  EXPECT_GT(seen.udp_sockets, 0);
  EXPECT_GT(seen.largest_segment, 0);
}

TEST(DdsProfile, ASharedMemoryOnlyProfileOpensNoUdpSocket) {
  const Transports seen = openedWith(profileWith("shm_only", kShm, "<transport_id>shm</transport_id>"),
                                     testDomain(DomainBlock::kDdsProfile, 1));
  ASSERT_FALSE(seen.failed);
  EXPECT_EQ(seen.udp_sockets, 0);
  EXPECT_GT(seen.largest_segment, 0);
}

TEST(DdsProfile, AUdpOnlyProfileMapsNoSharedMemory) {
  const Transports seen = openedWith(profileWith("udp_only", kUdp, "<transport_id>udp</transport_id>"),
                                     testDomain(DomainBlock::kDdsProfile, 2));
  ASSERT_FALSE(seen.failed);
  EXPECT_GT(seen.udp_sockets, 0);
  EXPECT_EQ(seen.largest_segment, 0);
}

TEST(DdsProfile, TheLargeDataProfileMapsItsSixteenMegabyteSegment) {
  const Transports seen = openedWith(sourcePath("config/dds/large_data.xml"), testDomain(DomainBlock::kDdsProfile, 3));
  ASSERT_FALSE(seen.failed);
  EXPECT_GE(seen.largest_segment, 16L * 1024 * 1024);
}

TEST(DdsProfile, AProfileNamingMissingCertificatesIsRefused) {
  const std::string path = freshDirectory("dds_profile_security") + "/missing_certificates.xml";
  std::ofstream(path) << "<?xml version=\"1.0\" encoding=\"UTF-8\" ?>\n"
                         "<dds xmlns=\"http://www.eprosima.com/XMLSchemas/fastRTPS_Profiles\"><profiles>\n"
                         "<participant profile_name=\"secure\" is_default_profile=\"true\"><rtps><propertiesPolicy>"
                         "<properties>"
                         "<property><name>dds.sec.auth.plugin</name><value>builtin.PKI-DH</value></property>"
                         "<property><name>dds.sec.auth.builtin.PKI-DH.identity_ca</name>"
                         "<value>file:///nonexistent/ca.pem</value></property>"
                         "<property><name>dds.sec.auth.builtin.PKI-DH.identity_certificate</name>"
                         "<value>file:///nonexistent/cert.pem</value></property>"
                         "<property><name>dds.sec.auth.builtin.PKI-DH.private_key</name>"
                         "<value>file:///nonexistent/key.pem</value></property>"
                         "</properties></propertiesPolicy></rtps></participant>\n"
                         "</profiles></dds>\n";
  EXPECT_TRUE(openedWith(path, testDomain(DomainBlock::kDdsProfile, 4)).failed);
}

}  // namespace
}  // namespace uampc::test
