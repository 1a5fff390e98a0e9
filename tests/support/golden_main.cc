// A gtest main for screenshot tests: link recon_golden_main instead of GTest::gtest_main so the
// binary accepts --update-goldens.

#include <gtest/gtest.h>

#include "tests/support/golden_image.h"

int main(int argc, char** argv) {
  // Before InitGoogleTest, so gtest never sees the flag.
  recon::testing::ParseGoldenFlags(&argc, argv);
  ::testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
