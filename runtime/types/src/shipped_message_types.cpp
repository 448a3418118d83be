// The runtime registers every shipped message package (idl/), so that it finds any of them by ROS
// name even when no loaded component uses it. Packages of a user's own IDL register themselves
// when their component library is loaded (see message_type.hpp).
#include "uampc/msgs/all.hpp"
