#include "engine/core/dataset.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "engine/core/error.h"

namespace recon {
namespace {

using ::testing::HasSubstr;

Dataset SmallDataset() {
  Dataset d;
  d.spec = {2, {3}, 1, 2};
  Episode e;
  e.samples.push_back({{0, 0}, {1, 2, 3}, {0.5f}, {1, 0}});
  e.samples.push_back({{1, 0}, {1, 2, 3}, {0.5f}, {1, 0}});
  d.demos.push_back(e);
  d.play.push_back({{0, 0}, {3, 2, 1}, {0.25f}});
  return d;
}

TEST(DatasetTest, ValidDatasetPasses) {
  const Dataset d = SmallDataset();
  EXPECT_NO_THROW(ValidateDataset(d));
  EXPECT_EQ(d.NumDemoSamples(), 2);
  EXPECT_EQ(d.spec.ToString(), "x 2, y 3, b 1, u 2");
}

TEST(DatasetTest, NanNamesEpisodeSampleAndField) {
  Dataset d = SmallDataset();
  d.demos[0].samples[1].u[1] = std::numeric_limits<float>::quiet_NaN();
  try {
    ValidateDataset(d, "demo.h5");
    FAIL() << "expected a UserError";
  } catch (const UserError& e) {
    EXPECT_THAT(e.what(), HasSubstr("demo.h5"));
    EXPECT_THAT(e.what(), HasSubstr("demonstration 0, sample 1"));
    EXPECT_THAT(e.what(), HasSubstr("'u'"));
  }
}

TEST(DatasetTest, InfiniteInPlayIsRejected) {
  Dataset d = SmallDataset();
  d.play[0].y[2] = std::numeric_limits<float>::infinity();
  EXPECT_THROW(ValidateDataset(d), UserError);
}

TEST(DatasetTest, WrongSizeIsRejected) {
  Dataset d = SmallDataset();
  d.demos[0].samples[0].b = {1, 2};
  try {
    ValidateDataset(d);
    FAIL();
  } catch (const UserError& e) {
    EXPECT_THAT(e.what(), HasSubstr("'b' has 2 values, expected 1"));
  }
}

TEST(DatasetTest, NoDemonstrationsIsRejected) {
  Dataset d = SmallDataset();
  d.demos.clear();
  EXPECT_THROW(ValidateDataset(d), UserError);
}

TEST(DatasetTest, FingerprintChangesWithAnyValue) {
  const Dataset a = SmallDataset();
  Dataset b = SmallDataset();
  EXPECT_EQ(Fingerprint(a), Fingerprint(b));
  b.play[0].b[0] = 0.26f;
  EXPECT_NE(Fingerprint(a), Fingerprint(b));
}

}  // namespace
}  // namespace recon
