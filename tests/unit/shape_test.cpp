#include "rbsf/dynamics/shape.h"

#include <gtest/gtest.h>

namespace rbsf {
namespace {
TEST(Shape, Placeholder) { EXPECT_EQ(EllipseShape(0.3, 0.15).type(), "ellipse"); }
}  // namespace
}  // namespace rbsf
