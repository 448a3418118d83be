#include <gtest/gtest.h>

#include "uampc/runtime/scene.hpp"

namespace uampc {
namespace {

TEST(Override, SplitsDottedNameAndValue) {
  const Override o = parseOverride("motor.encoder_rate=100");
  ASSERT_EQ(o.path.size(), 2u);
  EXPECT_EQ(o.path[0], "motor");
  EXPECT_EQ(o.path[1], "encoder_rate");
  EXPECT_EQ(o.value, "100");
  EXPECT_EQ(parseOverride("seed=7").path.size(), 1u);
  EXPECT_EQ(parseOverride("a.b=x=y").value, "x=y");
}

TEST(Override, RejectsMissingValueOrEmptyName) {
  EXPECT_THROW(parseOverride("motor.encoder_rate"), SceneError);
  EXPECT_THROW(parseOverride("=3"), SceneError);
  EXPECT_THROW(parseOverride("motor..rate=3"), SceneError);
}

}  // namespace
}  // namespace uampc
