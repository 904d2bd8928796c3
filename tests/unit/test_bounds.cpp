#include <preskin/Scene.h>

#include <gtest/gtest.h>

namespace preskin::test {

TEST(Bounds, ExtendAndCenter) {
    preskin::Bounds b;
    EXPECT_TRUE(b.empty());
    b.extend(glm::vec3(-1.0f, 2.0f, 0.5f));
    b.extend(glm::vec3(3.0f, -2.0f, 1.5f));
    EXPECT_FALSE(b.empty());
    EXPECT_EQ(b.center(), glm::vec3(1.0f, 0.0f, 1.0f));
    EXPECT_EQ(b.extent(), glm::vec3(4.0f, 4.0f, 1.0f));
    preskin::Bounds empty;
    b.extend(empty);
    EXPECT_EQ(b.extent(), glm::vec3(4.0f, 4.0f, 1.0f));
}

}  // namespace preskin::test
